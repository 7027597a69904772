// cmd_plot.cpp - `gmmrrt-learn plot MODEL -o IMAGE [--points FEATURES.csv] [--extent M]`: a picture
// of a model: its density on a grid with a colour bar, each component's one-sigma contour, and
// the training points if given.
//
// The numbers are computed here, by the C core the planner uses: the model is loaded and
// validated by gmmrrt_io (LoadModel), the density is gmmrrt_gmm_density_batch, and a
// (d, theta) model (kind features, what `fit` learns from demonstrations) is drawn in the
// person's frame (the person at the origin facing +x', their left up): every grid point is
// turned into (d, theta) by gmmrrt_features_from_xy, each contour mu + L (cos a, sin a) and each
// training point is mapped back by gmmrrt_features_to_xy. A generic 2-D model is drawn in its
// own coordinates; other D are refused. Drawing the image is left to matplotlib: the numbers
// go as JSON to a small renderer (plot_render.py, installed in <prefix>/share/gmmrrt beside
// <prefix>/bin) run by the system's python3, as Debian's python3-matplotlib provides it (a
// Recommends of the package: only this subcommand needs it). The renderer holds no rule of
// the model; it writes the image whole or not at all.
#include <getopt.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli_common.hpp"
#include "commands.hpp"
#include "gmmrrt/features.h"
#include "gmmrrt/gmm.h"
#include "gmmrrt_learner/features_csv.hpp"

extern char** environ;

namespace gmmrrt {
namespace learn {
namespace cli {

namespace {
const char kPlotHelp[] =
    "usage: gmmrrt-learn plot MODEL -o IMAGE [--points FEATURES.csv] [--extent M]\n"
    "\n"
    "Draws MODEL's density with a colour bar and each component's one-sigma contour into IMAGE\n"
    "(PNG, PDF or SVG by its suffix). A (d, theta) model is drawn in the person's frame (the person\n"
    "at the origin facing +x', their left up); a generic 2-D model in its own coordinates; other\n"
    "dimensions are refused.\n"
    "  -o, --output IMAGE     the image (written whole or not at all)\n"
    "  --points FEATURES.csv  training points to draw over it: the model's features, one point a\n"
    "                         line (as fit --features-csv reads them)\n"
    "  --extent M             half-width [m] of the person-frame view (default: from the components)\n"
    "Needs the system's python3 with matplotlib (Debian: apt-get install python3-matplotlib);\n"
    "GMMRRT_PYTHON3 names another interpreter.\n"
    "Exit status: 0 written; 1 a bad model or points, or the image could not be drawn; 2 usage.\n";

constexpr int kGrid = 161;       // grid points per side
constexpr int kContourSteps = 73;  // points per one-sigma contour (5 degree steps, closed)
constexpr double kPi = 3.14159265358979323846;

// Where the renderer is: <dir of this executable>/../share/gmmrrt/plot_render.py, in the build
// tree (bin/ and share/ side by side) as when installed.
std::string RendererPath() {
  std::vector<char> buf(4096);
  const ssize_t n = readlink("/proc/self/exe", buf.data(), buf.size() - 1);
  if (n <= 0) return std::string();
  std::string exe(buf.data(), static_cast<size_t>(n));
  const size_t slash = exe.find_last_of('/');
  return exe.substr(0, slash) + "/../share/gmmrrt/plot_render.py";
}

// Runs python3 RENDERER DATA IMAGE; returns its exit status (127: could not start it).
int RunRenderer(const std::string& python, const std::string& renderer, const std::string& data,
                const std::string& image) {
  std::vector<std::string> args = {python, renderer, data, image};
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(&a[0]);
  argv.push_back(nullptr);
  pid_t pid;
  if (posix_spawnp(&pid, python.c_str(), nullptr, nullptr, argv.data(), environ) != 0) return 127;
  int status = 0;
  while (waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) return 127;
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128;
}

nlohmann::json Xy(double x, double y) { return nlohmann::json::array({x, y}); }
}  // namespace

int RunPlot(int argc, char** argv) {
  const char* cmd = "plot";
  static const struct option kLong[] = {{"output", required_argument, nullptr, 'o'},
                                        {"points", required_argument, nullptr, 'p'},
                                        {"extent", required_argument, nullptr, 'e'},
                                        {"help", no_argument, nullptr, 'h'},
                                        {nullptr, 0, nullptr, 0}};
  optind = 1;
  std::string output, points_path;
  double extent = 0.0;
  int c;
  while ((c = getopt_long(argc, argv, "ho:", kLong, nullptr)) != -1) {
    if (c == 'h') {
      std::fputs(kPlotHelp, stdout);
      return kExitOk;
    }
    if (c == 'o') {
      output = optarg;
    } else if (c == 'p') {
      points_path = optarg;
    } else if (c == 'e') {
      if (!ParseDouble(optarg, &extent) || extent <= 0.0 || extent > 1000.0)
        return UsageError(cmd, std::string("--extent: '") + optarg + "' is not a half-width in (0, 1000] m");
    } else {
      return UsageError(cmd, "unknown option");
    }
  }
  if (output.empty()) return UsageError(cmd, "give the image file with -o");
  if (optind + 1 != argc) return UsageError(cmd, "give exactly one MODEL");
  const std::string model_path = argv[optind];

  std::unique_ptr<gmmrrt_model_t> model(new gmmrrt_model_t);
  Status s = LoadModel(model_path, model.get());
  if (!s.ok()) return Fail(cmd, s.message);
  if (model->dim != 2)
    return Fail(cmd, model_path + ": D = " + std::to_string(model->dim) + "; only D = 2 models are drawn");
  const bool person_frame = model->kind == GMMRRT_MODEL_KIND_FEATURES;
  const gmmrrt_pose_t origin = {0.0, 0.0, 0.0};
  Eigen::MatrixXd pts;
  if (!points_path.empty()) {
    s = ReadFeaturesCsv(points_path, &pts);
    if (!s.ok()) return Fail(cmd, s.message);
    if (pts.rows() != 2)
      return Fail(cmd, points_path + ": " + std::to_string(pts.rows()) + " columns, the model has 2");
  }
  const auto to_view = [&](double f0, double f1) {
    if (!person_frame) return Xy(f0, f1);
    double x, y;
    gmmrrt_features_to_xy(&origin, f0, f1, &x, &y);
    return Xy(x, y);
  };

  // One-sigma contours, and the extent of the view.
  nlohmann::json contours = nlohmann::json::array();
  double lo[2] = {HUGE_VAL, HUGE_VAL}, hi[2] = {-HUGE_VAL, -HUGE_VAL}, reach_m = 0.0;
  for (int i = 0; i < model->k; ++i) {
    const double* mu = model->mean[i];
    const double* L = model->chol[i];  // L00, L10, L11
    nlohmann::json line = nlohmann::json::array();
    for (int a = 0; a < kContourSteps; ++a) {
      const double ang = 2.0 * kPi * a / (kContourSteps - 1);
      const double u = std::cos(ang), v = std::sin(ang);
      const double f0 = mu[0] + L[0] * u, f1 = mu[1] + L[1] * u + L[2] * v;
      nlohmann::json p = to_view(f0, f1);
      for (int j = 0; j < 2; ++j) {
        lo[j] = std::min(lo[j], p[j].get<double>());
        hi[j] = std::max(hi[j], p[j].get<double>());
      }
      line.push_back(p);
    }
    contours.push_back(line);
    reach_m = std::max(reach_m, mu[0] + 2.0 * L[0]);  // d + 2 sigma_d (L00 = sigma_d)
  }
  double gx0, gx1, gy0, gy1;
  if (person_frame) {
    const double half = extent > 0.0 ? extent : std::min(8.0, std::max(1.0, 1.2 * reach_m));
    gx0 = gy0 = -half;
    gx1 = gy1 = half;
  } else {
    const double px = 0.15 * (hi[0] - lo[0]), py = 0.15 * (hi[1] - lo[1]);
    gx0 = lo[0] - px, gx1 = hi[0] + px, gy0 = lo[1] - py, gy1 = hi[1] + py;
  }

  // Density on the grid, row by row (rows: y), by the planner's batch kernel.
  nlohmann::json gx = nlohmann::json::array(), gy = nlohmann::json::array(), dens = nlohmann::json::array();
  std::vector<double> f0(kGrid), f1(kGrid), p(kGrid);
  for (int i = 0; i < kGrid; ++i) {
    gx.push_back(gx0 + (gx1 - gx0) * i / (kGrid - 1));
    gy.push_back(gy0 + (gy1 - gy0) * i / (kGrid - 1));
  }
  for (int r = 0; r < kGrid; ++r) {
    const double y = gy[r].get<double>();
    for (int i = 0; i < kGrid; ++i) {
      const double x = gx[i].get<double>();
      if (person_frame) {
        gmmrrt_features_from_xy(&origin, x, y, &f0[i], &f1[i]);
      } else {
        f0[i] = x;
        f1[i] = y;
      }
    }
    gmmrrt_gmm_density_batch(model.get(), f0.data(), f1.data(), kGrid, p.data());
    dens.push_back(p);
  }
  nlohmann::json points = nullptr;
  if (pts.cols() > 0) {
    points = nlohmann::json::array();
    for (Eigen::Index j = 0; j < pts.cols(); ++j) points.push_back(to_view(pts(0, j), pts(1, j)));
  }
  const std::string base = model_path.substr(model_path.find_last_of('/') + 1);
  const nlohmann::json doc = {
      {"title", base + ": K = " + std::to_string(model->k) + (person_frame ? ", (d, theta) features" : "")},
      {"xlabel", person_frame ? "x' [m] (person faces +x')" : "feature 1"},
      {"ylabel", person_frame ? "y' [m] (person's left)" : "feature 2"},
      {"colorbar", person_frame ? "density p(d, theta)" : "density"},
      {"person_frame", person_frame},
      {"grid_x", gx},
      {"grid_y", gy},
      {"density", dens},
      {"contours", contours},
      {"points", points}};

  // The numbers go through a private temporary file (the renderer reads it by name).
  const char* tmpdir = std::getenv("TMPDIR");
  std::string data_path = std::string(tmpdir && *tmpdir ? tmpdir : P_tmpdir) + "/gmmrrt-plot-XXXXXX";
  const int fd = mkstemp(&data_path[0]);
  if (fd < 0) return Fail(cmd, "cannot create a temporary file for the plot data: " + std::string(std::strerror(errno)));
  const std::string text = doc.dump();
  size_t done = 0;
  while (done < text.size()) {
    const ssize_t w = write(fd, text.data() + done, text.size() - done);
    if (w < 0 && errno == EINTR) continue;
    if (w <= 0) break;
    done += static_cast<size_t>(w);
  }
  const bool written = done == text.size();
  close(fd);
  if (!written) {
    unlink(data_path.c_str());
    return Fail(cmd, "cannot write the plot data to " + data_path);
  }
  const std::string renderer = RendererPath();
  const char* py_env = std::getenv("GMMRRT_PYTHON3");
  const std::string python = py_env && *py_env ? py_env : "/usr/bin/python3";
  if (renderer.empty() || access(renderer.c_str(), R_OK) != 0) {
    unlink(data_path.c_str());
    return Fail(cmd, "the renderer " + renderer + " is missing: a broken installation");
  }
  const int rc = RunRenderer(python, renderer, data_path, output);
  unlink(data_path.c_str());
  if (rc == 127) return Fail(cmd, "cannot run " + python + ": install python3 (or set GMMRRT_PYTHON3)");
  if (rc == 3)
    return Fail(cmd, python + " has no matplotlib: apt-get install python3-matplotlib (or set GMMRRT_PYTHON3)");
  if (rc != 0) return Fail(cmd, "drawing " + output + " failed (the renderer's reason is above)");
  std::fprintf(stderr, "gmmrrt-learn plot: wrote %s\n", output.c_str());
  return kExitOk;
}

}  // namespace cli
}  // namespace learn
}  // namespace gmmrrt
