"""`scripts/plot animate`: a top-down animation of one recorded episode (docs/traces.md).

    scripts/plot animate TRACE.json -o OUT.gif [--episode K] [--scenario S] [--max-frames N] [--fps F]
    scripts/plot animate TRACE.json -o OUT.png --frame K      (one frame as a picture)

Reads a "rapid.trace/1" file written by `rapid rollout --record` and draws, per decision, the road
around the ego (lanes from the network's real x/y shapes), every recorded vehicle as a box (the ego
red, SUMO's humans blue, cut-in obstacles orange), and below it the ego's speed, the action and the
reward over the episode with a cursor at the current decision. Long episodes are subsampled to at
most --max-frames frames (the last decision is always shown).

A trace that is not valid is rejected before anything is drawn, with one line
`plot animate: <file>: <problem>` on stderr and exit code 2: unreadable or truncated JSON, another
schema or format version, a missing or mistyped field, lengths that do not agree (an episode's
length and its decisions, a vehicle row and vehicle_fields), a road that is not its scenario's, or
a trace of another scenario than --scenario names.
"""
import argparse
import json
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.realpath(__file__)))
from scenario_files import scenario_edges, scenario_labels  # noqa: E402
from output_files import RefusedOutput, check_outputs, write_atomic  # noqa: E402

SCHEMA = "rapid.trace/1"
SCHEMA_PREFIX = "rapid.trace/"
VEHICLE_FIELDS = ["id", "type", "lane", "x", "y", "angle", "speed", "length", "width"]
# The edges of each built-in scenario's road, from its descriptor: a trace whose road is not its
# scenario's was recorded elsewhere or edited. (A scenario file of a user's is not checked.)
SCENARIO_EDGES = scenario_edges()
SCENARIO_LABEL = scenario_labels()


class BadTrace(Exception):
    """The one-line reason a trace is rejected."""


def _is_number(x):
    return isinstance(x, (int, float)) and not isinstance(x, bool) and math.isfinite(x)


def _need(obj, key, kind, where):
    if not isinstance(obj, dict) or key not in obj:
        raise BadTrace(f"{where}: missing field '{key}'")
    value = obj[key]
    ok = {
        "str": lambda v: isinstance(v, str),
        "int": lambda v: isinstance(v, int) and not isinstance(v, bool),
        "num": _is_number,
        "bool": lambda v: isinstance(v, bool),
        "list": lambda v: isinstance(v, list),
        "obj": lambda v: isinstance(v, dict),
    }[kind](value)
    if not ok:
        raise BadTrace(f"{where}: field '{key}' is not a {dict(str='string', int='whole number', num='number', bool='true/false', list='list', obj='JSON object')[kind]}")
    return value


def _check_vehicle(row, where):
    if not isinstance(row, list) or len(row) != len(VEHICLE_FIELDS):
        raise BadTrace(f"{where}: a vehicle row has {len(row) if isinstance(row, list) else 'no'} values, "
                       f"vehicle_fields names {len(VEHICLE_FIELDS)}")
    if not all(isinstance(v, str) for v in row[:3]) or not all(_is_number(v) for v in row[3:]):
        raise BadTrace(f"{where}: vehicle row {row[:1]} does not match vehicle_fields")


def _check_state(state, where):
    _need(state, "time", "num", where)
    _check_vehicle(_need(state, "ego", "list", where), where + ".ego")
    for row in _need(state, "vehicles", "list", where):
        _check_vehicle(row, where + ".vehicles")


def validate(trace, expect_scenario=None):
    """Raises BadTrace naming the first problem of a parsed trace."""
    if not isinstance(trace, dict):
        raise BadTrace("not a JSON object")
    schema = trace.get("schema")
    if not isinstance(schema, str):
        raise BadTrace("no 'schema' field: not a rapid trace")
    if schema != SCHEMA:
        if schema.startswith(SCHEMA_PREFIX):
            raise BadTrace(f"format version '{schema[len(SCHEMA_PREFIX):]}' is not supported (this script reads {SCHEMA})")
        raise BadTrace(f"schema is '{schema}', expected '{SCHEMA}'")
    scenario = _need(trace, "scenario", "str", "trace")
    if expect_scenario is not None and scenario != expect_scenario:
        raise BadTrace(f"is a trace of scenario '{scenario}', expected '{expect_scenario}'")
    settings = _need(trace, "settings", "obj", "trace")
    for key in ("action_repeat", "horizon"):
        _need(settings, key, "int", "settings")
    _need(settings, "desired_speed", "num", "settings")
    _need(trace, "policy", "str", "trace")
    _need(trace, "seed", "int", "trace")
    if _need(trace, "decision_seconds", "num", "trace") <= 0:
        raise BadTrace("decision_seconds must be positive")
    _need(trace, "sensing_range", "num", "trace")
    if _need(trace, "vehicle_fields", "list", "trace") != VEHICLE_FIELDS:
        raise BadTrace(f"vehicle_fields is {trace['vehicle_fields']}, expected {VEHICLE_FIELDS}")
    road = _need(trace, "road", "list", "trace")
    if not road:
        raise BadTrace("road has no edges")
    for edge in road:
        eid = _need(edge, "id", "str", "road")
        lanes = _need(edge, "lanes", "list", f"road edge '{eid}'")
        if not lanes:
            raise BadTrace(f"road edge '{eid}' has no lanes")
        for lane in lanes:
            where = f"road edge '{eid}' lane"
            _need(lane, "id", "str", where)
            _need(lane, "width", "num", where)
            shape = _need(lane, "shape", "list", where)
            if len(shape) < 2 or not all(isinstance(p, list) and len(p) == 2 and all(_is_number(c) for c in p) for p in shape):
                raise BadTrace(f"{where} '{lane['id']}': shape is not a list of at least two [x, y] points")
    junctions = _need(trace, "junctions", "list", "trace")
    for junction in junctions:
        jid = _need(junction, "id", "str", "junction")
        shape = _need(junction, "shape", "list", f"junction '{jid}'")
        if not all(isinstance(p, list) and len(p) == 2 and all(_is_number(c) for c in p) for p in shape):
            raise BadTrace(f"junction '{jid}': shape is not a list of [x, y] points")
    edges = {edge["id"] for edge in road}
    if scenario in SCENARIO_EDGES and edges != SCENARIO_EDGES[scenario]:
        raise BadTrace(f"road edges {sorted(edges)} are not the {scenario} road's {sorted(SCENARIO_EDGES[scenario])}")
    episodes = _need(trace, "episodes", "list", "trace")
    if not episodes:
        raise BadTrace("no episodes")
    for ep in episodes:
        index = _need(ep, "index", "int", "episode")
        where = f"episode {index}"
        length = _need(ep, "length", "int", where)
        _need(ep, "return", "num", where)
        _check_state(_need(ep, "start", "obj", where), where + ".start")
        decisions = _need(ep, "decisions", "list", where)
        if len(decisions) != length:
            raise BadTrace(f"{where}: length is {length} but {len(decisions)} decisions are recorded")
        total = 0.0
        for t, d in enumerate(decisions):
            w = f"{where} decision {t}"
            if _need(d, "t", "int", w) != t:
                raise BadTrace(f"{w}: t is {d['t']}, expected {t}")
            action = d.get("action", "missing")
            if action is not None and not (isinstance(action, list) and len(action) == 2 and all(_is_number(a) for a in action)):
                raise BadTrace(f"{w}: action is neither null nor two numbers")
            total += _need(d, "reward", "num", w)
            _need(d, "accel", "num", w)
            terms = _need(d, "terms", "obj", w)
            for key in ("velocity", "gap", "follower", "failed_lane_change", "collision"):
                _need(terms, key, "num", w + ".terms")
            for key in ("collision", "terminated", "truncated"):
                _need(d, key, "bool", w)
            _check_state(d, w)
        if abs(total - ep["return"]) > 1e-6 * max(1.0, abs(total)):
            raise BadTrace(f"{where}: return is {ep['return']} but its rewards sum to {total:.6f}")


def load_trace(path, expect_scenario=None):
    try:
        with open(path, "rb") as f:
            text = f.read()
    except OSError as e:
        raise BadTrace(f"cannot read it: {e.strerror}")
    try:
        trace = json.loads(text)
    except (ValueError, UnicodeDecodeError) as e:
        raise BadTrace(f"not valid JSON (truncated?): {e}")
    validate(trace, expect_scenario)
    return trace


# ----------------------------------------------------------------------------------------------
# Drawing

def _offset_polyline(points, d):
    """The polyline shifted sideways by d (left of the driving direction for d > 0)."""
    out = []
    n = len(points)
    for i, (x, y) in enumerate(points):
        # Normal from the neighbouring segments (averaged at inner points).
        nx = ny = 0.0
        for a, b in ((i - 1, i), (i, i + 1)):
            if 0 <= a and b < n:
                dx, dy = points[b][0] - points[a][0], points[b][1] - points[a][1]
                norm = math.hypot(dx, dy) or 1.0
                nx += -dy / norm
                ny += dx / norm
        norm = math.hypot(nx, ny) or 1.0
        out.append((x + d * nx / norm, y + d * ny / norm))
    return out


def _vehicle_corners(row):
    """Box corners of a vehicle row: (x, y) is the front bumper, angle SUMO's heading."""
    _, _, _, x, y, angle, _, length, width = row
    theta = math.radians(90.0 - angle)
    cx, cy = math.cos(theta), math.sin(theta)
    px, py = -cy, cx  # left of the heading
    hw = width / 2.0
    bx, by = x - length * cx, y - length * cy
    return [(x + hw * px, y + hw * py), (x - hw * px, y - hw * py), (bx - hw * px, by - hw * py), (bx + hw * px, by + hw * py)]


def _frame_indices(n_decisions, max_frames):
    """Frames: 0 is the start state, k the state after decision k-1; at most max_frames, last kept."""
    count = n_decisions + 1
    if count <= max_frames:
        return list(range(count))
    stride = math.ceil(count / max_frames)
    frames = list(range(0, count, stride))
    if frames[-1] != count - 1:
        if len(frames) >= max_frames:
            frames[-1] = count - 1
        else:
            frames.append(count - 1)
    return frames


class Animator:
    """Draws frames of one episode; each frame's figure is returned as a PIL image."""

    def __init__(self, trace, episode, width_px=880, dpi=100):
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        from matplotlib.collections import PolyCollection

        self.plt = plt
        self.trace, self.ep = trace, episode
        self.R = float(trace["sensing_range"])
        self.dt = float(trace["decision_seconds"])
        self.v_des = float(trace["settings"]["desired_speed"])
        self.states = [episode["start"]] + episode["decisions"]
        self.half_width = self.R  # metres shown on each side of the ego: the sensing range
        self.fig = plt.figure(figsize=(width_px / dpi, width_px / dpi * 0.7), dpi=dpi)
        grid = self.fig.add_gridspec(4, 1, height_ratios=[4.2, 1, 1, 1], hspace=0.12,
                                     left=0.075, right=0.985, top=0.94, bottom=0.075)
        self.ax = self.fig.add_subplot(grid[0])
        box = self.ax.get_position()
        fig_w, fig_h = self.fig.get_size_inches()
        self.aspect = (box.width * fig_w) / (box.height * fig_h)  # road view: width / height, metres alike
        self.strips = [self.fig.add_subplot(grid[i]) for i in (1, 2, 3)]
        self.road_artists = self._draw_road(PolyCollection)
        self._draw_strips()
        self.others = PolyCollection([], facecolors=[], edgecolors="#1b2a3a", linewidths=0.6, zorder=3)
        self.ego = PolyCollection([], facecolors="#e0201b", edgecolors="black", linewidths=1.2, zorder=4)
        self.ax.add_collection(self.others)
        self.ax.add_collection(self.ego)
        self.title = self.fig.text(box.x0, box.y1 + 0.012, "", fontsize=9, ha="left", va="bottom")
        self.background = None  # the figure without what changes per frame, drawn once

    def _draw_road(self, PolyCollection):
        ax = self.ax
        ax.set_facecolor("#dfe8d8")  # grass
        surface, edges, dashes = [], [], []
        for edge in self.trace["road"]:
            lanes = sorted(edge["lanes"], key=lambda lane: lane.get("index", 0))
            for i, lane in enumerate(lanes):
                pts = [tuple(p) for p in lane["shape"]]
                hw = lane["width"] / 2.0
                left, right = _offset_polyline(pts, hw), _offset_polyline(pts, -hw)
                surface.append(left + right[::-1])
                # Right border solid for the rightmost lane, left border solid for the leftmost;
                # dashed between lanes of one edge.
                if i == 0:
                    edges.append(right)
                if i == len(lanes) - 1:
                    edges.append(left)
                else:
                    dashes.append(left)
        junctions = [[tuple(p) for p in j["shape"]] for j in self.trace["junctions"] if len(j["shape"]) >= 3]
        artists = [ax.add_collection(PolyCollection(surface + junctions, facecolors="#6b6f73", edgecolors="#6b6f73",
                                                    linewidths=0.5, zorder=1))]
        for line in edges:
            xs, ys = zip(*line)
            artists += ax.plot(xs, ys, color="white", linewidth=1.2, zorder=2, solid_capstyle="butt")
        for line in dashes:
            xs, ys = zip(*line)
            artists += ax.plot(xs, ys, color="white", linewidth=0.9, zorder=2, dashes=(6, 6))
        # Equal scales come from the limits (draw() keeps their ratio at the box's), not from
        # set_aspect, so the box never moves between frames.
        ax.set_xticks([])
        ax.set_yticks([])
        for spine in ax.spines.values():
            spine.set_visible(False)
        self.centre_lines = [[tuple(p) for p in lane["shape"]] for edge in self.trace["road"] for lane in edge["lanes"]]
        return artists

    def _draw_strips(self):
        decisions = self.ep["decisions"]
        t = [self.dt * (k + 1) for k in range(len(decisions))]
        t0 = [0.0] + t
        speeds = [self.ep["start"]["ego"][6]] + [d["ego"][6] for d in decisions]
        sp, ac, rw = self.strips
        sp.plot(t0, speeds, color="#e0201b", linewidth=1.4)
        sp.axhline(self.v_des, color="gray", linestyle=":", linewidth=1)
        sp.set_ylabel("speed\nm/s", fontsize=8)
        if any(d["action"] is not None for d in decisions):
            ac.plot(t, [d["action"][0] if d["action"] else 0 for d in decisions], color="#1f77b4", linewidth=1.2,
                    label="a0 (accel.)")
            ac.plot(t, [d["action"][1] if d["action"] else 0 for d in decisions], color="#2ca02c", linewidth=1.0,
                    label="a1 (lane)")
            ac.axhline(1 / 3, color="#2ca02c", linestyle=":", linewidth=0.7)
            ac.axhline(-1 / 3, color="#2ca02c", linestyle=":", linewidth=0.7)
            ac.set_ylim(-1.15, 1.15)
            ac.set_ylabel("action", fontsize=8)
        else:  # SUMO's driver: no action; its realised acceleration instead
            ac.plot(t, [d["accel"] for d in decisions], color="#1f77b4", linewidth=1.2, label="accel. (SUMO driver)")
            ac.set_ylabel("accel.\nm/s²", fontsize=8)
        ac.legend(fontsize=7, loc="upper right", ncol=2, frameon=False)
        rw.plot(t, [d["reward"] for d in decisions], color="#7f3fbf", linewidth=1.2)
        rw.axhline(0, color="gray", linewidth=0.6)
        rw.set_ylabel("reward", fontsize=8)
        rw.set_xlabel("time since the ego entered (s)", fontsize=8)
        for ax in self.strips:
            ax.set_xlim(0, max(t0[-1], self.dt))
            ax.tick_params(labelsize=7)
            ax.grid(alpha=0.25)
        for ax in self.strips[:-1]:
            ax.tick_params(labelbottom=False)
        self.cursors = [ax.axvline(0, color="black", linewidth=1) for ax in self.strips]

    def _view_y(self, x0, x1, ego_y, height):
        """Centre of the view: the middle of the road's lanes within [x0, x1], the ego kept in view."""
        ys = []
        for line in self.centre_lines:
            for (ax, ay), (bx, by) in zip(line, line[1:]):
                lo, hi = max(min(ax, bx), x0), min(max(ax, bx), x1)
                if lo > hi:
                    continue
                for x in (lo, hi):
                    ys.append(ay if bx == ax else ay + (by - ay) * (x - ax) / (bx - ax))
        if not ys:
            return ego_y
        mid = (min(ys) + max(ys)) / 2
        # Keep the ego in view when the road in the window is taller than the view.
        margin = height / 2 - 6
        return min(max(mid, ego_y - margin), ego_y + margin)

    def draw(self, k):
        state = self.states[k]
        ego = state["ego"]
        x0, x1 = ego[3] - self.half_width, ego[3] + self.half_width
        height = (x1 - x0) / self.aspect
        yc = self._view_y(x0, x1, ego[4], height)
        self.ax.set_xlim(x0, x1)
        self.ax.set_ylim(yc - height / 2, yc + height / 2)
        colors = {"obstacle": "#f28e2b", "ego": "#e0201b"}
        self.others.set_verts([_vehicle_corners(v) for v in state["vehicles"]])
        self.others.set_facecolors([colors.get(v[1], "#6fa8dc") for v in state["vehicles"]])
        self.ego.set_verts([_vehicle_corners(ego)])
        t = 0.0 if k == 0 else self.dt * k
        for c in self.cursors:
            c.set_xdata([t, t])
        ret = sum(d["reward"] for d in self.ep["decisions"][:k])
        end = ""
        if k == len(self.states) - 1 and k > 0:
            last = self.ep["decisions"][-1]
            end = "  COLLISION" if last["collision"] else ("  (end)" if last["truncated"] else "")
        label = SCENARIO_LABEL.get(self.trace["scenario"], self.trace["scenario"])
        policy = os.path.basename(self.trace["policy"])
        self.title.set_text(f"{label} · policy {policy} · episode {self.ep['index']} · t = {t:5.1f} s · "
                            f"lane {ego[2]} · {ego[6]:4.1f} m/s · return {ret:6.1f}{end}")

    def image(self, k):
        """Frame k as a PIL image. The strips' axes, ticks and curves are drawn once; a frame redraws
        only the road view, the title and the cursors on top (blitting: most of the cost of a
        matplotlib draw is in axes and tick labels)."""
        from PIL import Image

        canvas = self.fig.canvas
        if self.background is None:
            moving = [self.ax, self.title] + self.cursors
            for a in moving:
                a.set_visible(False)
            canvas.draw()
            self.background = canvas.copy_from_bbox(self.fig.bbox)
            for a in moving:
                a.set_visible(True)
        self.draw(k)
        canvas.restore_region(self.background)
        for a in [self.ax.patch] + self.road_artists + [self.others, self.ego]:
            self.ax.draw_artist(a)
        self.fig.draw_artist(self.title)
        for c in self.cursors:
            c.axes.draw_artist(c)
        return Image.frombuffer("RGBA", canvas.get_width_height(), canvas.buffer_rgba()).convert("RGB")


def _quantized(images):
    """The frames in one shared palette (no dithering), so the GIF stores only what changes."""
    from PIL import Image

    # The palette: from a few frames side by side, so colours that appear late (an obstacle, a
    # collision) are in it too.
    sample = images[:: max(1, len(images) // 8)]
    w, h = sample[0].size
    sheet = Image.new("RGB", (w * len(sample), h))
    for i, im in enumerate(sample):
        sheet.paste(im, (i * w, 0))
    palette = sheet.quantize(colors=48, method=Image.Quantize.MEDIANCUT, dither=Image.Dither.NONE)
    return [im.quantize(palette=palette, dither=Image.Dither.NONE) for im in images]


def main(argv, prog="plot animate"):
    parser = argparse.ArgumentParser(prog=f"scripts/{prog}", description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("trace", help="a rapid.trace/1 file (rapid rollout --record)")
    parser.add_argument("-o", "--out", required=True, help="OUT.gif (animation) or OUT.png (one frame, see --frame)")
    parser.add_argument("--episode", type=int, help="the episode's index in the trace (default: its first)")
    parser.add_argument("--scenario", help="reject a trace of any other scenario")
    parser.add_argument("--max-frames", type=int, default=300, help="subsample longer episodes (default 300)")
    parser.add_argument("--fps", type=float, default=10.0, help="GIF frames per second (default 10)")
    parser.add_argument("--frame", type=int, help="PNG output: the state after this many decisions (default: the middle)")
    args = parser.parse_args(argv)

    def fail(problem, code=2):
        print(f"{prog}: {args.trace}: {problem}", file=sys.stderr)
        return code

    ext = os.path.splitext(args.out)[1].lower()
    if ext not in (".gif", ".png"):
        print(f"{prog}: -o {args.out}: the output must end in .gif or .png", file=sys.stderr)
        return 2
    if args.max_frames < 2 or args.fps <= 0:
        print(f"{prog}: --max-frames must be at least 2 and --fps positive", file=sys.stderr)
        return 2
    out_dir = os.path.dirname(os.path.abspath(args.out))
    if not os.path.isdir(out_dir):
        print(f"{prog}: -o {args.out}: folder '{out_dir}' does not exist", file=sys.stderr)
        return 2
    try:
        check_outputs([args.out])
    except RefusedOutput as e:
        print(f"{prog}: -o {e}", file=sys.stderr)
        return 2
    try:
        trace = load_trace(args.trace, args.scenario)
    except BadTrace as e:
        return fail(str(e))
    episodes = trace["episodes"]
    if args.episode is None:
        episode = episodes[0]
    else:
        matching = [ep for ep in episodes if ep["index"] == args.episode]
        if not matching:
            return fail(f"has no episode {args.episode} (it holds {[ep['index'] for ep in episodes]})")
        episode = matching[0]
    n = len(episode["decisions"])
    if args.frame is not None and not 0 <= args.frame <= n:
        return fail(f"--frame {args.frame}: episode {episode['index']} has frames 0..{n}")
    try:
        import matplotlib  # noqa: F401
        import PIL  # noqa: F401
    except ImportError as e:
        print(f"{prog}: needs matplotlib and Pillow (python3-matplotlib, python3-pil): {e}", file=sys.stderr)
        return 1

    animator = Animator(trace, episode)
    if ext == ".png":
        def write(f):
            animator.image(n // 2 if args.frame is None else args.frame).save(f, format="PNG", optimize=True)
    else:
        frames = _quantized([animator.image(k) for k in _frame_indices(n, args.max_frames)])
        duration = round(1000.0 / args.fps)
        # The last frame lingers, so the ending can be read before the loop restarts.
        durations = [duration] * (len(frames) - 1) + [max(duration, 2000)]

        def write(f):
            frames[0].save(f, format="GIF", save_all=True, append_images=frames[1:], duration=durations, loop=0,
                           optimize=False)
    try:
        write_atomic(args.out, write)
    except RefusedOutput as e:  # something was put at the output's name while the frames were drawn
        print(f"{prog}: -o {e}", file=sys.stderr)
        return 2
    print(f"wrote {args.out}")
    return 0
