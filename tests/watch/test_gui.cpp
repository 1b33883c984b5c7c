// `rapid rollout --gui`: the episode in sumo-gui, headless under Xvfb. The screenshot taken while
// it runs is not blank (it shows the road and the red ego), and the episode is the one libsumo
// runs: its trace is byte-identical.
#include <gtest/gtest.h>

#include "tests/watch/watch_test_util.hpp"

namespace rapid {
namespace {

using test::run_shell;
using test::Scratch;

TEST(GuiUnderXvfb, ScreenshotOfARunningEpisodeIsNotBlank) {
  if (run_shell("command -v xvfb-run").exit_code != 0)
    GTEST_SKIP() << "xvfb-run is missing: apt-get install xvfb xauth (scripts/setup.sh installs them)";
  Scratch s;
  const std::string args = "rollout --scenario merge --policy sumo --episodes 1 --seed 0 --json";
  const test::Run gui = run_shell("xvfb-run -a -s '-screen 0 1600x900x24' " +
                                  test::rapid(args + " --gui --gui-delay 0 --screenshot " + s / "shot.png --screenshot-at 25 --record " +
                                              s / "gui.json"),
                                  /*with_stderr=*/false);
  ASSERT_EQ(gui.exit_code, 0) << gui.out;
  ASSERT_TRUE(std::filesystem::exists(s / "shot.png")) << "no screenshot";
  // Not blank: several colours (sumo-gui draws flat: grass, road, markings, cars; 8 measured),
  // real contrast, and the red ego among them.
  const test::Run stats = run_shell(
      "/usr/bin/python3 -c 'from PIL import Image, ImageStat; im = Image.open(\"" + s / "shot.png" +
      "\").convert(\"RGB\"); c = im.getcolors(1 << 24); red = sum(n for n, (r, g, b) in c if r > 180 and g < 80 and b < 80); "
      "print(len(c), max(ImageStat.Stat(im).stddev), red, *im.size)'");
  if (stats.exit_code != 0) GTEST_SKIP() << "/usr/bin/python3 has no Pillow (python3-pil): " << stats.out;
  std::istringstream in(stats.out);
  int colours = 0, red = 0, width = 0, height = 0;
  double stddev = 0;
  in >> colours >> stddev >> red >> width >> height;
  RecordProperty("screenshot", stats.out);
  EXPECT_GE(colours, 5) << stats.out;
  EXPECT_GT(stddev, 10.0) << stats.out;
  EXPECT_GE(red, 20) << "the ego (red) is not in the picture: " << stats.out;
  EXPECT_GE(width, 640);
  // The same episode as libsumo's, to the byte.
  const test::Run plain = run_shell(test::rapid(args + " --record " + s / "plain.json"), false);
  ASSERT_EQ(plain.exit_code, 0);
  EXPECT_EQ(plain.out, gui.out) << "stdout differs (libtraci's messages must go to stderr)";
  EXPECT_EQ(test::slurp(s / "gui.json"), test::slurp(s / "plain.json"));
}

}  // namespace
}  // namespace rapid
