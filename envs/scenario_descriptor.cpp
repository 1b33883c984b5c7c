#include "envs/scenario_descriptor.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <set>
#include <sstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "core/atomic_file.hpp"
#include "core/hash.hpp"
#include "core/json_input.hpp"
#include "core/printable.hpp"

#ifndef RAPID_NETWORK_DIR
#define RAPID_NETWORK_DIR "networks"
#endif

namespace rapid {

namespace fs = std::filesystem;
using nlohmann::json;

std::string network_dir() {
  if (const char* dir = std::getenv("RAPID_NETWORK_DIR"); dir != nullptr && *dir != '\0') return dir;
  return RAPID_NETWORK_DIR;
}

std::vector<std::string> builtin_scenario_names() {
  std::vector<std::string> names;
  std::error_code error;  // no folder: no built-in scenario (scenario_descriptor says what to build)
  for (const auto& entry : fs::directory_iterator(network_dir(), error))
    if (entry.is_directory(error) && fs::is_regular_file(entry.path() / "scenario.json", error))
      names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

const std::vector<std::string>& feature_kind_names() {
  static const std::vector<std::string> names = {"distance_to_edge", "distance_to_lane_end"};
  return names;
}

const std::vector<std::string>& neighbour_lane_names() {
  static const std::vector<std::string> names = {"left", "current", "right"};
  return names;
}

const std::vector<std::string>& reward_term_names() {
  static const std::vector<std::string> names = {"offset", "gap", "failed_lane_change", "collision"};
  return names;
}

driving::RewardWeights scenario_reward_weights(const ScenarioDescriptor& d, const std::string& name) {
  const auto own = d.rewards.find(name);
  return own != d.rewards.end() ? own->second : driving::reward_weights(name);
}

const std::vector<std::string>& scenario_hook_names() {
  static const std::vector<std::string> names = {kCutInObstaclesHook};
  return names;
}

bool is_scenario_file(const std::string& name) { return name.size() > 5 && name.ends_with(".json"); }

namespace {

// Reads one descriptor, every failure an std::invalid_argument "<field>: <problem>" (the caller
// adds the file).
class Reader {
 public:
  explicit Reader(fs::path dir) : dir_(std::move(dir)) {}

  // The object at `key` of `parent` (`where` names it), every key of it one of `allowed` (any key
  // if `allowed` is empty).
  const json& object(const json& parent, const std::string& key, const std::string& where,
                     const std::vector<std::string>& allowed, bool required = true) const {
    static const json empty = json::object();
    if (!parent.contains(key)) {
      if (required) fail(where, "is missing");
      return empty;
    }
    const json& o = parent.at(key);
    if (!o.is_object()) fail(where, "must be an object");
    if (!allowed.empty()) only(o, where, allowed);
    return o;
  }

  void only(const json& o, const std::string& where, const std::vector<std::string>& allowed) const {
    for (const auto& [k, v] : o.items())
      if (std::find(allowed.begin(), allowed.end(), k) == allowed.end())
        fail(where.empty() ? k : where + "." + k, "unknown field (expected one of " + comma_joined(allowed) + ")");
  }

  std::string text(const json& o, const std::string& key, const std::string& where, const std::string& fallback = {},
                   bool required = true) const {
    if (!o.contains(key)) {
      if (required) fail(where, "is missing");
      return fallback;
    }
    const json& v = o.at(key);
    if (!v.is_string() || v.get<std::string>().empty()) fail(where, "must be a non-empty string");
    return v.get<std::string>();
  }

  double number(const json& o, const std::string& key, const std::string& where, double fallback, double lo,
                double hi, bool lo_open = false) const {
    if (!o.contains(key)) return fallback;
    const json& v = o.at(key);
    if (!v.is_number()) fail(where, "must be a number");
    const double x = v.get<double>();
    if (!std::isfinite(x) || x < lo || (lo_open && x == lo) || x > hi)
      fail(where, "must be " + std::string(lo_open ? "above " : "from ") + short_text(lo) + " to " + short_text(hi));
    return x;
  }

  int integer(const json& o, const std::string& key, const std::string& where, int fallback, int lo, int hi) const {
    if (!o.contains(key)) return fallback;
    const json& v = o.at(key);
    const std::optional<long long> i = json_integer(v);
    if (!i || *i < lo || *i > hi) fail(where, "must be a whole number from " + std::to_string(lo) + " to " + std::to_string(hi));
    return static_cast<int>(*i);
  }

  // A path relative to the descriptor's folder, which must name an existing file.
  std::string file(const json& o, const std::string& key, const std::string& where) const {
    const fs::path path = (dir_ / text(o, key, where)).lexically_normal();
    std::error_code ec;  // a symlink loop makes the throwing overload say "Too many levels…" with exit 1 (issue 46)
    const bool regular = fs::is_regular_file(path, ec);
    if (ec && ec != std::errc::no_such_file_or_directory)
      fail(where, path.string() + " cannot be read: " + ec.message());
    if (!regular && fs::exists(fs::symlink_status(path, ec)))
      fail(where, path.string() + " is not a regular file (a FIFO, device or folder would not be read as one)");
    if (!regular) fail(where, "no such file " + path.string());
    return path.string();
  }

  [[noreturn]] static void fail(const std::string& where, const std::string& problem) {
    throw std::invalid_argument(where + ": " + problem);
  }

  static std::string short_text(double x) {
    std::ostringstream s;
    s << x;
    return s.str();
  }

 private:
  fs::path dir_;
};

// The value of attribute `name` in one XML start tag's text, or "". Scanned by hand: libstdc++'s
// std::regex recurses once per character of a match, so a route of 10,000 edges (a 50 kB
// attribute) overflowed the stack (issue 46).
std::string attribute(const std::string& tag, const std::string& name) {
  const auto space = [](char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; };
  for (auto at = tag.find(name); at != std::string::npos; at = tag.find(name, at + 1)) {
    if (at == 0 || !space(tag[at - 1])) continue;
    std::size_t i = at + name.size();
    while (i < tag.size() && space(tag[i])) ++i;
    if (i >= tag.size() || tag[i] != '=') continue;
    ++i;
    while (i < tag.size() && space(tag[i])) ++i;
    if (i >= tag.size() || tag[i] != '"') continue;
    const auto close = tag.find('"', i + 1);
    if (close == std::string::npos) return "";
    return tag.substr(i + 1, close - i - 1);
  }
  return "";
}

// The start tags <`element` …> of an XML text (SUMO's files are flat enough for this: the
// descriptor only asks which ids exist).
std::vector<std::string> start_tags(const std::string& xml, const std::string& element) {
  std::vector<std::string> tags;
  const std::string open = "<" + element;
  for (auto at = xml.find(open); at != std::string::npos; at = xml.find(open, at + 1)) {
    const char next = at + open.size() < xml.size() ? xml[at + open.size()] : '>';
    if (next != ' ' && next != '\t' && next != '\n' && next != '\r' && next != '>' && next != '/') continue;
    const auto end = xml.find('>', at);
    if (end == std::string::npos) break;
    tags.push_back(xml.substr(at, end - at + 1));
  }
  return tags;
}

// A file the descriptor names, read whole (bounded, regular files only): a file that cannot be read
// is a wrong descriptor, one line naming the field (exit 2), not a failed run.
std::string read_named_file(const std::string& path, const std::string& where) {
  try {
    return read_file(path);
  } catch (const std::runtime_error& e) {
    Reader::fail(where, e.what());
  }
}

// The ids of the network's normal edges and their lanes. A network with junction-internal lanes
// (edges ':…') is refused: the env needs every vehicle on one of the road's edges.
std::map<std::string, int> network_edges(const std::string& net_file, const std::string& where) {
  const std::string xml = read_named_file(net_file, where);
  if (xml.find("function=\"internal\"") != std::string::npos)
    Reader::fail(where, net_file + " has junction-internal lanes: build it with netconvert --no-internal-links true");
  std::map<std::string, int> edges;
  const std::string open = "<edge";
  for (auto at = xml.find(open); at != std::string::npos; at = xml.find(open, at + 1)) {
    const auto tag_end = xml.find('>', at);
    if (tag_end == std::string::npos) break;
    const std::string tag = xml.substr(at, tag_end - at + 1);
    const std::string id = attribute(tag, "id");
    if (id.empty() || id[0] == ':' || !attribute(tag, "function").empty()) continue;
    const auto close = xml.find("</edge>", tag_end);
    const std::string body = xml.substr(tag_end, close == std::string::npos ? std::string::npos : close - tag_end);
    edges[id] = static_cast<int>(start_tags(body, "lane").size());
  }
  return edges;
}

// route id → its edges, from a routes file's text.
std::map<std::string, std::vector<std::string>> routes_of(const std::string& routes_xml) {
  std::map<std::string, std::vector<std::string>> routes;
  for (const std::string& tag : start_tags(routes_xml, "route")) {
    std::istringstream edges(attribute(tag, "edges"));
    std::vector<std::string> list;
    for (std::string e; edges >> e;) list.push_back(e);
    routes[attribute(tag, "id")] = list;
  }
  return routes;
}

// The vehicle type ids defined in some SUMO files' texts.
std::set<std::string> vtype_ids(const std::vector<std::string>& xml_texts) {
  std::set<std::string> ids;
  for (const std::string& xml : xml_texts)
    for (const std::string& tag : start_tags(xml, "vType")) ids.insert(attribute(tag, "id"));
  return ids;
}

// A setting of the descriptor's "settings" object, checked for its type; the ranges are checked
// with the whole (validate_scenario_settings).
void read_setting(ScenarioSettings& s, const std::string& key, const json& v) {
  auto number = [&](double& field) {
    if (!v.is_number()) Reader::fail("settings." + key, "must be a number");
    field = v.get<double>();
  };
  auto integer = [&](int& field) {
    const std::optional<long long> i = json_integer(v);
    if (!i || std::abs(*i) > 1'000'000'000LL) Reader::fail("settings." + key, "must be a whole number");
    field = static_cast<int>(*i);
  };
  auto text = [&](std::string& field) {
    if (!v.is_string()) Reader::fail("settings." + key, "must be a string");
    field = v.get<std::string>();
  };
  if (key == "network") text(s.network);
  else if (key == "reward") text(s.reward);
  else if (key == "action_repeat") integer(s.action_repeat);
  else if (key == "horizon") integer(s.horizon);
  else if (key == "lane_change_interval") integer(s.lane_change_interval);
  else if (key == "traffic_warmup") integer(s.traffic_warmup);
  else if (key == "obstacles") integer(s.obstacles);
  else if (key == "max_depart_delay") number(s.max_depart_delay);
  else if (key == "desired_speed") number(s.desired_speed);
  else if (key == "inflow") number(s.inflow);
  else if (key == "ramp_inflow") number(s.ramp_inflow);
  else if (key == "obstacle_speed_min") number(s.obstacle_speed_min);
  else if (key == "obstacle_speed_max") number(s.obstacle_speed_max);
  else Reader::fail("settings." + key, "unknown setting (docs/scenarios.md lists them)");
}

FeatureSpec read_feature(const Reader& r, const json& f, const std::string& where) {
  if (!f.is_object()) Reader::fail(where, "must be an object");
  FeatureSpec spec;
  const std::string kind = r.text(f, "kind", where + ".kind");
  if (kind == "distance_to_edge") {
    r.only(f, where, {"kind", "edge", "range"});
    spec.kind = FeatureSpec::Kind::kDistanceToEdge;
    spec.edge = r.text(f, "edge", where + ".edge");
    if (!f.contains("range")) Reader::fail(where + ".range", "is missing");
    spec.range = r.number(f, "range", where + ".range", 0.0, 0.0, 1e6, true);
  } else if (kind == "distance_to_lane_end") {
    r.only(f, where, {"kind", "edge", "lane", "range", "range_from"});
    spec.kind = FeatureSpec::Kind::kDistanceToLaneEnd;
    spec.edge = r.text(f, "edge", where + ".edge");
    spec.lane = r.integer(f, "lane", where + ".lane", 0, 0, 100);
    if (f.contains("range") == f.contains("range_from"))
      Reader::fail(where, "give exactly one of range (m) and range_from (an edge)");
    spec.range = r.number(f, "range", where + ".range", 0.0, 0.0, 1e6, true);
    spec.range_from = r.text(f, "range_from", where + ".range_from", "", false);
  } else {
    Reader::fail(where + ".kind", "unknown feature '" + printable(kind) + "' (expected one of " +
                                      comma_joined(feature_kind_names()) + ")");
  }
  return spec;
}

ScenarioDescriptor read_descriptor(const std::string& path) {
  const fs::path file = fs::absolute(path).lexically_normal();
  const json doc = read_json_input(file.string());
  if (!doc.is_object()) Reader::fail("the descriptor", "must be a JSON object");
  const Reader r(file.parent_path());
  r.only(doc, "", {"description", "name", "display_name", "networks", "additional_files", "road", "ego",
                   "step_length", "traffic", "observation", "action", "hook", "rewards", "settings", "profiles"});
  ScenarioDescriptor d;
  d.file = file.string();
  d.name = r.text(doc, "name", "name");
  d.display_name = r.text(doc, "display_name", "display_name", d.name, false);
  // The name names folders (jobs/<name>/…); both reach every report format.
  if (!is_safe_name(d.name)) Reader::fail("name", "must use only letters, digits, '.', '_' and '-' (it names folders)");
  if (!is_plain_text(d.display_name))
    Reader::fail("display_name", "may use only letters, digits, spaces and - _ . , ( ) + / : ' (it is printed in LaTeX, "
                                 "markdown, CSV and HTML tables)");

  const json& networks = r.object(doc, "networks", "networks", {});
  if (networks.empty()) Reader::fail("networks", "must name at least one network");
  for (const auto& [variant, files] : networks.items()) {
    const std::string where = "networks." + variant;
    // A variant's name is a config value: it reaches folder names (a grid axis) and every table.
    if (!is_safe_name(variant))
      Reader::fail(where, "a network's name may use only letters, digits, '.', '_' and '-' (it names folders and table cells)");
    if (!files.is_object()) Reader::fail(where, "must be an object with net and routes");
    r.only(files, where, {"net", "routes"});
    d.networks[variant] = {r.file(files, "net", where + ".net"), r.file(files, "routes", where + ".routes")};
  }
  if (doc.contains("additional_files")) {
    const json& list = doc.at("additional_files");
    if (!list.is_array()) Reader::fail("additional_files", "must be an array of paths");
    for (std::size_t i = 0; i < list.size(); ++i) {
      const json entry = {{"f", list[i]}};
      d.additional_files.push_back(r.file(entry, "f", "additional_files[" + std::to_string(i) + "]"));
    }
  }

  if (!doc.contains("road") || !doc.at("road").is_array() || doc.at("road").empty())
    Reader::fail("road", "must be a non-empty array of edge ids");
  for (const json& e : doc.at("road")) {
    if (!e.is_string() || e.get<std::string>().empty()) Reader::fail("road", "must hold edge ids (strings)");
    d.road.push_back(e.get<std::string>());
  }

  const json& ego = r.object(doc, "ego", "ego", {"route", "type", "depart_lane"});
  d.ego.route = r.text(ego, "route", "ego.route");
  d.ego.type = r.text(ego, "type", "ego.type", "ego", false);
  if (ego.contains("depart_lane") && !(ego.at("depart_lane").is_string() && ego.at("depart_lane") == "random"))
    d.ego.depart_lane = r.integer(ego, "depart_lane", "ego.depart_lane", 0, 0, 100);

  // SUMO counts time in milliseconds: a shorter step would be passed to it as 0 (1e-300 once was).
  d.step_length = r.number(doc, "step_length", "step_length", 0.1, 0.001, 10.0);
  const json& traffic = r.object(doc, "traffic", "traffic", {"warmup_jitter"}, false);
  d.traffic_warmup_jitter = r.integer(traffic, "warmup_jitter", "traffic.warmup_jitter", 50, 0, 100000);

  const json& obs = r.object(doc, "observation", "observation",
                             {"sensing_range", "lane_end_range", "speed_norm", "rel_speed_norm", "neighbours", "features"},
                             false);
  d.sensing_range = r.number(obs, "sensing_range", "observation.sensing_range", 100.0, 0.0, 10000.0, true);
  d.lane_end_range = r.number(obs, "lane_end_range", "observation.lane_end_range", 200.0, 0.0, 100000.0, true);
  d.speed_norm = r.number(obs, "speed_norm", "observation.speed_norm", 35.0, 0.0, 100.0, true);
  d.rel_speed_norm = r.number(obs, "rel_speed_norm", "observation.rel_speed_norm", 15.0, 0.0, 100.0, true);
  if (obs.contains("neighbours")) {
    const json& list = obs.at("neighbours");
    if (!list.is_array()) Reader::fail("observation.neighbours", "must be an array of left, current, right");
    d.neighbour_lanes.clear();
    for (std::size_t i = 0; i < list.size(); ++i) {
      const std::string where = "observation.neighbours[" + std::to_string(i) + "]";
      const auto& names = neighbour_lane_names();
      const auto it = list[i].is_string() ? std::find(names.begin(), names.end(), list[i].get<std::string>()) : names.end();
      if (it == names.end()) Reader::fail(where, "unknown neighbour lane " + json_excerpt(list[i]) + " (expected one of " + comma_joined(names) + ")");
      const int side = static_cast<int>(it - names.begin());
      if (!d.neighbour_lanes.empty() && side <= d.neighbour_lanes.back())
        Reader::fail(where, "give each lane once, in the order left, current, right");
      d.neighbour_lanes.push_back(side);
    }
  }
  if (obs.contains("features")) {
    const json& list = obs.at("features");
    if (!list.is_array()) Reader::fail("observation.features", "must be an array");
    for (std::size_t i = 0; i < list.size(); ++i)
      d.features.push_back(read_feature(r, list[i], "observation.features[" + std::to_string(i) + "]"));
  }

  const json& action = r.object(doc, "action", "action", {"max_accel", "lane_change_threshold"}, false);
  d.max_accel = r.number(action, "max_accel", "action.max_accel", 4.0, 0.0, 20.0, true);
  if (action.contains("lane_change_threshold"))
    d.lane_change_threshold =
        static_cast<float>(r.number(action, "lane_change_threshold", "action.lane_change_threshold", 0.0, 0.0, 1.0, true));

  if (doc.contains("hook")) {
    d.hook = r.text(doc, "hook", "hook");
    const auto& hooks = scenario_hook_names();
    if (std::find(hooks.begin(), hooks.end(), d.hook) == hooks.end())
      Reader::fail("hook", "unknown hook '" + printable(d.hook) + "' (expected one of " + comma_joined(hooks) + ")");
  }

  // Reward variants of its own: each term optional, defaulting to the `short` variant's weight.
  const json& rewards = r.object(doc, "rewards", "rewards", {}, false);
  for (const auto& [name, terms] : rewards.items()) {
    const std::string where = "rewards." + name;
    if (!is_safe_name(name))
      Reader::fail(where, "a reward variant's name may use only letters, digits, '.', '_' and '-' (it names folders and table cells)");
    const auto& builtin = reward_variants();
    if (std::find(builtin.begin(), builtin.end(), name) != builtin.end())
      Reader::fail(where, "'" + name + "' is a built-in reward variant; give yours another name");
    if (!terms.is_object()) Reader::fail(where, "must be an object of reward terms and their weights");
    for (const auto& [term, weight] : terms.items())
      if (std::find(reward_term_names().begin(), reward_term_names().end(), term) == reward_term_names().end())
        Reader::fail(where + "." + term, "unknown reward term (expected one of " + comma_joined(reward_term_names()) + ")");
    driving::RewardWeights w = driving::reward_weights("short");
    w.offset = r.number(terms, "offset", where + ".offset", w.offset, -10.0, 10.0);
    w.gap = r.number(terms, "gap", where + ".gap", w.gap, 0.0, 100.0);
    w.failed_lane_change = r.number(terms, "failed_lane_change", where + ".failed_lane_change", w.failed_lane_change, 0.0, 100.0);
    w.collision = r.number(terms, "collision", where + ".collision", w.collision, 0.0, 10000.0);
    d.rewards[name] = w;
  }

  // The network-independent checks first; then the files: the road's edges, the ego's route.
  // Each routes file is read once, here; its text also serves the vehicle-type check below.
  std::vector<std::string> vtype_texts;
  for (const std::string& f : d.additional_files) vtype_texts.push_back(read_named_file(f, "additional_files"));
  for (const auto& [variant, files] : d.networks) {
    const auto edges = network_edges(files.net, "networks." + variant + ".net");
    for (const std::string& e : d.road)
      if (!edges.contains(e)) Reader::fail("road", "edge '" + printable(e) + "' is not in " + files.net);
    auto check_edge = [&](const std::string& e, const std::string& where) {
      if (std::find(d.road.begin(), d.road.end(), e) == d.road.end())
        Reader::fail(where, "edge '" + printable(e) + "' is not one of the road's edges");
    };
    for (std::size_t i = 0; i < d.features.size(); ++i) {
      const FeatureSpec& f = d.features[i];
      const std::string where = "observation.features[" + std::to_string(i) + "]";
      check_edge(f.edge, where + ".edge");
      if (!f.range_from.empty()) check_edge(f.range_from, where + ".range_from");
      if (f.kind == FeatureSpec::Kind::kDistanceToLaneEnd && f.lane >= edges.at(f.edge))
        Reader::fail(where + ".lane", "edge '" + f.edge + "' has " + std::to_string(edges.at(f.edge)) + " lanes");
    }
    const std::string& routes_xml = vtype_texts.emplace_back(read_named_file(files.routes, "networks." + variant + ".routes"));
    const auto routes = routes_of(routes_xml);
    const auto route = routes.find(d.ego.route);
    if (route == routes.end()) Reader::fail("ego.route", "route '" + printable(d.ego.route) + "' is not in " + files.routes);
    if (route->second.empty()) Reader::fail("ego.route", "route '" + d.ego.route + "' has no edges");
    for (const std::string& e : route->second)
      if (!edges.contains(e)) Reader::fail("ego.route", "edge '" + printable(e) + "' of route '" + d.ego.route + "' is not in " + files.net);
    if (!d.ego.depart_edge.empty() && d.ego.depart_edge != route->second.front())
      Reader::fail("ego.route", "starts on '" + route->second.front() + "' in " + files.routes + " but on '" +
                                    d.ego.depart_edge + "' in another network");
    d.ego.depart_edge = route->second.front();
    if (std::find(d.road.begin(), d.road.end(), d.ego.depart_edge) == d.road.end())
      Reader::fail("ego.route", "starts on '" + d.ego.depart_edge + "', which is not one of the road's edges: the ego could never be observed");
    if (d.ego.depart_lane >= edges.at(d.ego.depart_edge))
      Reader::fail("ego.depart_lane", "the ego's first edge '" + d.ego.depart_edge + "' has " +
                                          std::to_string(edges.at(d.ego.depart_edge)) + " lanes");
    if (routes_xml.find("\"RAMP_INFLOW\"") != std::string::npos) d.has_ramp_inflow = true;
  }
  const std::set<std::string> vtypes = vtype_ids(vtype_texts);
  if (!vtypes.contains(d.ego.type))
    Reader::fail("ego.type", "vehicle type '" + printable(d.ego.type) + "' is in none of the routes and additional files");
  if (d.hook == kCutInObstaclesHook && !vtypes.contains(kObstacleType))
    Reader::fail("hook", std::string(kCutInObstaclesHook) + " needs a vehicle type '" + kObstacleType +
                             "' in the routes or additional files");

  const json& settings = r.object(doc, "settings", "settings", {}, false);
  // One network is the default; of several, the settings say which.
  if (d.networks.size() > 1 && !settings.contains("network"))
    Reader::fail("settings.network", "is missing: say which of the networks is the default");
  d.defaults.network = d.networks.begin()->first;
  for (const auto& [key, value] : settings.items()) read_setting(d.defaults, key, value);
  try {
    validate_scenario_settings(d, d.defaults);
  } catch (const std::invalid_argument& e) {
    Reader::fail("settings", e.what());
  }
  const json& profiles = r.object(doc, "profiles", "profiles", {}, false);
  for (const auto& [profile, overrides] : profiles.items())
    if (!overrides.is_object()) Reader::fail("profiles." + profile, "must be an object of config keys");
  d.profiles = profiles;
  return d;
}

}  // namespace

std::vector<std::string> scenario_network_names(const ScenarioDescriptor& d) {
  std::vector<std::string> names;
  for (const auto& [variant, files] : d.networks) names.push_back(variant);
  return names;
}

std::vector<std::string> scenario_reward_names(const ScenarioDescriptor& d) {
  std::vector<std::string> names = reward_variants();
  for (const auto& [variant, weights] : d.rewards) names.push_back(variant);
  return names;
}

ScenarioDescriptor read_scenario_descriptor(const std::string& path) {
  try {
    return read_descriptor(path);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument("scenario file " + path + ": " + e.what());
  }
}

namespace {
std::mutex& registry_mutex() {
  static std::mutex mutex;
  return mutex;
}
// Names a grid gave to scenario files → the files' absolute paths.
std::map<std::string, std::string>& registered_files() {
  static std::map<std::string, std::string> files;
  return files;
}
}  // namespace

void register_scenario_file(const std::string& name, const std::string& path) {
  const std::string absolute = fs::absolute(path).lexically_normal().string();
  const auto d = scenario_descriptor(absolute);
  if (d->name != name)
    throw std::invalid_argument("scenario file " + absolute + ": name: '" + printable(d->name) + "', but it is given as '" +
                                printable(name) + "'");
  std::lock_guard<std::mutex> lock(registry_mutex());
  auto& files = registered_files();
  if (const auto it = files.find(name); it != files.end() && it->second != absolute)
    throw std::invalid_argument("scenario '" + name + "' is already the file " + it->second);
  files[name] = absolute;
}

bool is_registered_scenario(const std::string& name) {
  std::lock_guard<std::mutex> lock(registry_mutex());
  return registered_files().contains(name);
}

std::string scenario_files_hash(const ScenarioDescriptor& d) {
  // Once per descriptor file and process, like the descriptor itself (scenario_descriptor()): a
  // sweep's state checks ask for it once per job.
  static std::mutex mutex;
  static std::map<std::string, std::string> hashes;
  std::lock_guard<std::mutex> lock(mutex);
  if (const auto it = hashes.find(d.file); it != hashes.end()) return it->second;
  std::string all = read_file(d.file);
  for (const auto& [variant, files] : d.networks) all += "\n" + read_file(files.net) + "\n" + read_file(files.routes);
  for (const std::string& f : d.additional_files) all += "\n" + read_file(f);
  return hashes[d.file] = fnv1a_hex(all);
}

std::shared_ptr<const ScenarioDescriptor> scenario_descriptor(const std::string& name) {
  static std::mutex mutex;
  static std::map<std::string, std::shared_ptr<const ScenarioDescriptor>> cache;
  std::string registered;
  {
    std::lock_guard<std::mutex> lock(registry_mutex());
    if (const auto it = registered_files().find(name); it != registered_files().end()) registered = it->second;
  }
  if (!registered.empty()) return scenario_descriptor(registered);
  const std::string path = is_scenario_file(name) ? name : network_dir() + "/" + name + "/scenario.json";
  std::error_code exists_error;
  if (!is_scenario_file(name) && !fs::exists(path, exists_error))
    throw std::invalid_argument("scenario '" + printable(name) + "': its descriptor " + path +
                                " is missing: build the 'rapid_networks' target or set RAPID_NETWORK_DIR");
  const std::string key = fs::absolute(path).lexically_normal().string();
  std::lock_guard<std::mutex> lock(mutex);
  if (const auto it = cache.find(key); it != cache.end()) return it->second;
  auto d = std::make_shared<const ScenarioDescriptor>(read_scenario_descriptor(path));
  if (!is_scenario_file(name) && d->name != name)
    throw std::invalid_argument("scenario file " + path + ": name: '" + printable(d->name) + "', but it is the descriptor of '" + name + "'");
  cache[key] = d;
  return d;
}

}  // namespace rapid
