// report.html opened as a reader opens it: Debian's chromium, headless, at 1400 px and at a
// phone's 390 px. The page must load without a script or resource error, every image
// (all embedded) must decode, and the page must not scroll sideways (wide tables scroll in
// their own box). Skips, saying so, where chromium is not installed
// (`bash scripts/setup.sh --with-browser`).
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <regex>

#include "core/atomic_file.hpp"
#include "render/figures_sweep.hpp"
#include "render/report.hpp"
#include "render/run_pictures.hpp"
#include "render/sweep_folder.hpp"
#include "tests/render/synthetic_run.hpp"
#include "tests/render/synthetic_sweep.hpp"
#include "tests/support/slambox_cli.hpp"

namespace slambox::render {
namespace {

namespace fs = std::filesystem;

std::string Chromium() {
  for (const char* exe : {"/usr/bin/chromium", "/usr/bin/chromium-browser"})
    if (fs::exists(exe)) return exe;
  return "";
}

// Appended to a copy of the page: counts the images that decoded, catches every error
// (scripts and, in the capture phase, resources) and whether the page is wider than the window.
constexpr const char* kProbe = R"(<script>
var probeErrors = 0;
window.addEventListener('error', function () { probeErrors++; }, true);
window.addEventListener('load', function () {
  var imgs = Array.prototype.slice.call(document.images);
  var ok = imgs.filter(function (i) { return i.complete && i.naturalWidth > 0; }).length;
  var wide = document.documentElement.scrollWidth > window.innerWidth + 1;
  document.body.setAttribute('data-probe', 'images ' + ok + '/' + imgs.length + ' errors ' + probeErrors +
                             ' overflow ' + (wide ? 1 : 0) + ' width ' + window.innerWidth);
});
</script>)";

struct Probe {
  int exit_code = -1;
  std::string result;  ///< "images N/M errors E overflow O width W", empty when the page did not load
};

// Headless chromium's window is at least 500 px wide: the page is shown in a frame of the
// width asked for (its viewport, media queries included), and the frame's probe result
// is copied out to the top page that --dump-dom prints.
std::string Frame(const std::string& page, int width_px) {
  return "<!DOCTYPE html><html><body style=\"margin:0\"><iframe id=\"f\" src=\"" + page + "\" width=\"" +
         std::to_string(width_px) + "\" height=\"900\" style=\"border:0\"></iframe><script>"
         "document.getElementById('f').addEventListener('load', function () {"
         "  var b = this.contentDocument && this.contentDocument.body;"
         "  document.body.setAttribute('data-probe', b ? b.getAttribute('data-probe') : 'no access');"
         "});</script></body></html>";
}

Probe OpenInChromium(const std::string& html_path, int width_px, const fs::path& scratch) {
  std::string page = testing::ReadText(html_path);
  page.insert(page.rfind("</body>"), kProbe);
  const fs::path probe = scratch / "probe.html", frame = scratch / ("frame_" + std::to_string(width_px) + ".html");
  WriteFileAtomic(probe.string(), page);
  WriteFileAtomic(frame.string(), Frame("probe.html", width_px));
  const std::string cmd = "timeout 120 " + Chromium() + " --headless --no-sandbox --disable-gpu --hide-scrollbars" +
                          " --allow-file-access-from-files --user-data-dir=" + (scratch / "profile").string() +
                          " --window-size=" + std::to_string(width_px + 50) +
                          ",1000 --virtual-time-budget=10000 --dump-dom file://" + frame.string() + " 2>/dev/null";
  Probe out;
  std::string dom;
  if (FILE* p = popen(cmd.c_str(), "r")) {
    char buf[65536];
    for (size_t n; (n = fread(buf, 1, sizeof buf, p)) > 0;) dom.append(buf, n);
    const int status = pclose(p);
    out.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }
  std::smatch m;
  if (std::regex_search(dom, m, std::regex("data-probe=\"([^\"]*)\""))) out.result = m[1];
  return out;
}

TEST(ReportInBrowser, RendersWithEveryImageAtDesktopAndPhoneWidth) {
  if (Chromium().empty())
    GTEST_SKIP() << "chromium is not installed (bash scripts/setup.sh --with-browser): report.html not opened";
  const fs::path dir = testing::FreshTempDir("browser");
  testing::WriteSyntheticSweep(dir.string());
  const fs::path run = dir / "template_run";
  testing::WriteSyntheticRun(run.string());
  RenderRunPictures(ReadRunFolder(run.string()), run.string());
  for (const auto& r : ReadSweepFolder(dir.string()).results.rows)
    if (!fs::exists(dir / "runs" / r.run_id)) {
      fs::create_directories(dir / "runs" / r.run_id / kPicturesDir);
      fs::copy(run / kPicturesDir, dir / "runs" / r.run_id / kPicturesDir);
    }
  RenderSweepFigures(dir.string());
  WriteReport(dir.string());
  const std::string html = testing::ReadText(dir / "report.html");
  size_t images = 0;
  for (size_t p = 0; (p = html.find("<img ", p)) != std::string::npos; ++p) ++images;
  ASSERT_GT(images, 20u);  // 2 scenarios x 6 grid points x 2 pictures + the sweep figures
  for (int width : {1400, 390}) {
    const Probe p = OpenInChromium((dir / "report.html").string(), width, dir);
    EXPECT_EQ(p.exit_code, 0) << width << " px";
    EXPECT_EQ(p.result, "images " + std::to_string(images) + "/" + std::to_string(images) + " errors 0 overflow 0 width " +
                            std::to_string(width))
        << width << " px (empty: the page did not load)";
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace slambox::render
