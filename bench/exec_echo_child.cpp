// The exec benchmark's child (bench/exec_overhead_bench.cpp): reads the protocol's lines,
// integrates odometry (no motion model: the point is the protocol, not the math) and
// answers one pose with a covariance per odometry event, as cheaply as C allows.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace {

double Field(const char* line, const char* key) {
  const char* at = std::strstr(line, key);
  return at ? std::strtod(at + std::strlen(key), nullptr) : 0.0;
}

}  // namespace

int main() {
  static char out_buffer[1 << 16];
  std::setvbuf(stdout, out_buffer, _IOFBF, sizeof out_buffer);
  char* line = nullptr;
  std::size_t capacity = 0;
  double x = 0.0, y = 0.0, theta = 0.0, variance = 0.0;
  while (getline(&line, &capacity, stdin) > 0) {
    if (std::strncmp(line, "{\"type\":\"odometry\"", 18) == 0) {
      const double t = Field(line, "\"t_s\":"), dx = Field(line, "\"dx_m\":"), dy = Field(line, "\"dy_m\":"),
                   dth = Field(line, "\"dtheta_rad\":");
      const double c = std::cos(theta), s = std::sin(theta);
      x += c * dx - s * dy, y += s * dx + c * dy, theta = std::remainder(theta + dth, 2 * M_PI);
      variance += 1e-6;
      std::printf(
          "{\"type\":\"pose\",\"t_s\":%.17g,\"x_m\":%.17g,\"y_m\":%.17g,\"theta_rad\":%.17g,"
          "\"covariance\":[%.17g,0.0,0.0,0.0,%.17g,0.0,0.0,0.0,%.17g]}\n",
          t, x, y, theta, variance, variance, variance);
    } else if (std::strncmp(line, "{\"type\":\"finish\"", 16) == 0) {
      std::printf("{\"type\":\"done\"}\n");
      break;
    } else if (std::strncmp(line, "{\"type\":\"header\"", 16) == 0) {
      x = Field(line, "\"start_pose\":["), theta = 0.0;
      std::printf("{\"type\":\"pose\",\"t_s\":0.0,\"x_m\":%.17g,\"y_m\":0.0,\"theta_rad\":0.0}\n", x);
    }
  }
  std::fflush(stdout);
  std::free(line);
  return 0;
}
