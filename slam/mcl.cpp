#include "slam/mcl.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "core/error.hpp"
#include "core/limits.hpp"
#include "core/odometry_model.hpp"
#include "slam/map_points.hpp"
#include "slam/particle_weights.hpp"

namespace slambox {

void BindParams(MclConfig& c, ParamBinder& b) {
  b.Bind("particles", c.particles, "-", "number of particles M");
  b.Bind("sigma_hit_m", c.sigma_hit_m, "m", "likelihood field: std of an endpoint's distance to the nearest wall");
  b.Bind("z_hit", c.z_hit, "-", "weight of the hit term (1 - z_hit: uniform random returns)");
  b.Bind("max_distance_m", c.max_distance_m, "m", "likelihood field distance clamp");
  b.Bind("grid_resolution_m", c.grid_resolution_m, "m", "likelihood field cell size");
  b.Bind("beam_step", c.beam_step, "-", "use every beam_step-th beam");
  b.Bind("neff_threshold", c.neff_threshold, "fraction of M", "resample when N_eff < neff_threshold * M");
  b.Bind("motion_noise_scale", c.motion_noise_scale, "-", "factor on the odometry model's covariance");
  b.Bind("init_sigma_xy_m", c.init_sigma_xy_m, "m", "initial particle spread around the start, position");
  b.Bind("init_sigma_theta_deg", c.init_sigma_theta_deg, "deg", "initial particle spread, heading");
  b.Bind("recovery_alpha_slow", c.recovery_alpha_slow, "-", "augmented MCL: long-term likelihood average rate (0 = off)");
  b.Bind("recovery_alpha_fast", c.recovery_alpha_fast, "-", "augmented MCL: short-term likelihood average rate (0 = off)");
  b.Bind("free_clearance_m", c.free_clearance_m, "m", "random particles keep this distance from every wall");
}

Mcl::Mcl(const MclConfig& config) : config_(config) {
  auto fail = [](const char* field, const char* fix) {
    throw InputError(std::string("--set algo.mcl.") + field, 0, "invalid value", fix);
  };
  if (config_.particles < 1 || config_.particles > limits::kMaxParticles)
    fail("particles", ("set particles to 1 .. " + std::to_string(limits::kMaxParticles) + " (e.g. 500)").c_str());
  if (!(config_.sigma_hit_m > 0)) fail("sigma_hit_m", "give a positive std (e.g. 0.05)");
  if (!(config_.z_hit > 0 && config_.z_hit <= 1)) fail("z_hit", "z_hit lies in (0, 1]");
  if (!(config_.max_distance_m > 0) || !(config_.grid_resolution_m > 0)) fail("max_distance_m", "must be > 0");
  if (config_.beam_step < 1) fail("beam_step", "set beam_step >= 1");
  if (!(config_.neff_threshold >= 0 && config_.neff_threshold <= 1)) fail("neff_threshold", "lies in [0, 1]");
  if (config_.motion_noise_scale < 0 || config_.init_sigma_xy_m < 0 || config_.init_sigma_theta_deg < 0)
    fail("motion_noise_scale", "noise scales and spreads must not be negative");
  if (config_.recovery_alpha_slow < 0 || config_.recovery_alpha_fast > 1 ||
      (config_.recovery_alpha_fast > 0 && !(config_.recovery_alpha_slow > 0 && config_.recovery_alpha_slow < config_.recovery_alpha_fast)))
    fail("recovery_alpha_slow", "use 0 < recovery_alpha_slow < recovery_alpha_fast <= 1 (e.g. 0.001 and 0.1), or both 0");
  if (!(config_.free_clearance_m >= 0 && config_.free_clearance_m < config_.max_distance_m))
    fail("free_clearance_m", "must lie in [0, max_distance_m)");
}

void Mcl::Start(const StreamHeader& header) {
  // Wall points 1 cm apart (or finer than a quarter cell): the field is exact to ~1 mm.
  const std::vector<Eigen::Vector2d> walls = SampleWorldOutlines(header.world, std::min(0.01, 0.25 * config_.grid_resolution_m));
  if (walls.size() < 10)
    throw InputError(header.scenario_name, 0, "mcl needs a known map, and this stream's world has no walls",
                     "run it on a simulated scenario (a converted real log carries no map)");
  field_ = MakeDistanceGrid(walls, config_.grid_resolution_m, config_.max_distance_m, config_.max_distance_m);
  map_lo_ = map_hi_ = walls.front();
  for (const auto& w : walls) map_lo_ = map_lo_.cwiseMin(w), map_hi_ = map_hi_.cwiseMax(w);
  w_slow_ = w_fast_ = 0.0;
  alpha_ = header.sensors.odometry ? header.sensors.odometry->alpha : std::array<double, 4>{};
  // The beam's log-likelihood depends on its endpoint's wall distance d alone:
  // log(z_hit N(d; 0, sigma_hit) + z_rand / z_max), tabulated once over [0, max_distance]
  // (the field's clamp) and interpolated linearly, so the hot loop has no log or exp.
  const double range_max_m = header.sensors.lidar ? header.sensors.lidar->range_max_m : 30.0;
  const double z_rand = (1.0 - config_.z_hit) / range_max_m;
  const double norm = config_.z_hit / (std::sqrt(2 * M_PI) * config_.sigma_hit_m);
  beam_log_likelihood_.resize(kBeamTableSize + 1);
  for (int k = 0; k <= kBeamTableSize; ++k) {
    const double d = config_.max_distance_m * k / kBeamTableSize;
    beam_log_likelihood_[k] = std::log(norm * std::exp(-0.5 * d * d / (config_.sigma_hit_m * config_.sigma_hit_m)) + z_rand);
  }
  // Own generator: the stream seed and this module's name.
  std::seed_seq seq{static_cast<std::uint32_t>(header.seed), static_cast<std::uint32_t>(header.seed >> 32), 0x6d636cu};
  rng_.seed(seq);
  std::normal_distribution<double> n01(0.0, 1.0);
  poses_.assign(config_.particles, header.start_pose);
  for (SE2& p : poses_)
    p = SE2(p.x + config_.init_sigma_xy_m * n01(rng_), p.y + config_.init_sigma_xy_m * n01(rng_),
            p.theta + config_.init_sigma_theta_deg * M_PI / 180.0 * n01(rng_));
  log_weights_.assign(config_.particles, 0.0);
  estimate_ = Estimate{};
  Record(0.0);
}

// The estimate: weighted mean (circular heading) and covariance of the particles near the
// heaviest 1 m cell (within 2 cells of it), so that a multi-modal cloud (random particles
// of Augmented MCL, a lost filter) reports its main mode rather than a point between modes.
void Mcl::Record(double t_s) {
  const std::vector<double> w = NormalizeLogWeights(log_weights_);
  const auto cell = [](const SE2& p) {
    return std::make_pair(static_cast<long>(std::floor(p.x)), static_cast<long>(std::floor(p.y)));
  };
  std::map<std::pair<long, long>, double> mass;
  for (size_t i = 0; i < w.size(); ++i) mass[cell(poses_[i])] += w[i];
  const auto best = std::max_element(mass.begin(), mass.end(), [](const auto& a, const auto& b) { return a.second < b.second; })->first;
  std::vector<size_t> mode;
  double total = 0.0;
  for (size_t i = 0; i < w.size(); ++i) {
    const auto c = cell(poses_[i]);
    if (std::abs(c.first - best.first) <= 2 && std::abs(c.second - best.second) <= 2) mode.push_back(i), total += w[i];
  }
  double x = 0, y = 0, s = 0, c = 0;
  for (size_t i : mode) {
    const double wi = w[i] / total;
    x += wi * poses_[i].x, y += wi * poses_[i].y, s += wi * std::sin(poses_[i].theta), c += wi * std::cos(poses_[i].theta);
  }
  PoseEstimate e{t_s, SE2(x, y, std::atan2(s, c)), Eigen::Matrix3d::Zero(), true};
  for (size_t i : mode) {
    const Eigen::Vector3d d(poses_[i].x - x, poses_[i].y - y, NormalizeAngle(poses_[i].theta - e.pose.theta));
    e.covariance += w[i] / total * d * d.transpose();
  }
  if (!estimate_.trajectory.empty() && estimate_.trajectory.back().t_s == t_s) estimate_.trajectory.back() = e;
  else estimate_.trajectory.push_back(e);
}

void Mcl::OnOdometry(const OdometryEvent& odometry) {
  const OdometryIncrement u = Decompose(odometry.delta);
  const Eigen::Vector3d sd = (config_.motion_noise_scale * IncrementCovariance(u, alpha_)).diagonal().cwiseSqrt();
  std::normal_distribution<double> n01(0.0, 1.0);
  for (SE2& p : poses_) {  // Thrun Table 5.6: sample noisy (rot1, trans, rot2)
    const OdometryIncrement noisy{u.rot1 + sd(0) * n01(rng_), u.trans + sd(1) * n01(rng_), u.rot2 + sd(2) * n01(rng_)};
    p = PredictMotion(p, noisy).pose;
  }
  Record(odometry.t_s);
}

void Mcl::OnLaserScan(const LaserScanEvent& scan) {
  // Likelihood field: the sum of the used beams' log-likelihoods (the table from Start);
  // misses carry no information here and are skipped.
  const double cells_per_m = kBeamTableSize / config_.max_distance_m;
  std::vector<Eigen::Vector2d> endpoints;  // in the robot frame
  for (size_t b = 0; b < scan.ranges_m.size(); b += static_cast<size_t>(config_.beam_step)) {
    if (!scan.valid[b]) continue;
    const double a = scan.angle_min_rad + static_cast<double>(b) * scan.angle_increment_rad;
    endpoints.emplace_back(scan.ranges_m[b] * std::cos(a), scan.ranges_m[b] * std::sin(a));
  }
  double w_avg = 0.0;  // mean over particles of the per-beam geometric-mean likelihood
  for (size_t i = 0; i < poses_.size(); ++i) {
    double ll = 0.0;
    for (const Eigen::Vector2d& q : endpoints) {
      const double f = std::min(field_.At(poses_[i] * q) * cells_per_m, static_cast<double>(kBeamTableSize));
      const int k = std::min(static_cast<int>(f), kBeamTableSize - 1);
      ll += beam_log_likelihood_[k] + (f - k) * (beam_log_likelihood_[k + 1] - beam_log_likelihood_[k]);
    }
    log_weights_[i] += ll;
    if (!endpoints.empty()) w_avg += std::exp(ll / static_cast<double>(endpoints.size())) / static_cast<double>(poses_.size());
  }
  // Thrun Table 8.3: w_slow, w_fast follow w_avg; a sudden drop (w_fast << w_slow) means
  // the particles are lost, and 1 - w_fast / w_slow of them are replaced at resampling.
  double random_fraction = 0.0;
  if (config_.recovery_alpha_fast > 0 && !endpoints.empty()) {
    if (w_slow_ == 0.0) w_slow_ = w_fast_ = w_avg;
    w_slow_ += config_.recovery_alpha_slow * (w_avg - w_slow_);
    w_fast_ += config_.recovery_alpha_fast * (w_avg - w_fast_);
    random_fraction = w_slow_ > 0 ? std::max(0.0, 1.0 - w_fast_ / w_slow_) : 0.0;
  }
  const std::vector<double> w = NormalizeLogWeights(log_weights_);
  const double neff = EffectiveSampleSize(w);
  const bool resample = neff < config_.neff_threshold * static_cast<double>(poses_.size()) || random_fraction > 0.0;
  Record(scan.t_s);  // the weighted estimate before resampling (resampling adds noise only)
  if (resample) {
    std::vector<SE2> next;
    next.reserve(poses_.size());
    for (int k : LowVarianceResample(w, rng_)) next.push_back(poses_[static_cast<size_t>(k)]);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    int injected = 0;
    for (SE2& p : next)
      if (u(rng_) < random_fraction) p = RandomFreePose(), ++injected;
    poses_ = std::move(next);
    estimate_.diagnostics["random_particles"].emplace_back(scan.t_s, injected);
    log_weights_.assign(poses_.size(), 0.0);
  } else {
    for (size_t i = 0; i < w.size(); ++i) log_weights_[i] = std::log(std::max(w[i], 1e-300));
  }
  estimate_.diagnostics["neff"].emplace_back(scan.t_s, neff);
  estimate_.diagnostics["resampled"].emplace_back(scan.t_s, resample ? 1.0 : 0.0);
}

// Uniform over the walls' bounding box and heading, at least free_clearance_m from every
// wall (rejection sampling; after 1000 tries the last draw is taken).
SE2 Mcl::RandomFreePose() {
  std::uniform_real_distribution<double> ux(map_lo_.x(), map_hi_.x()), uy(map_lo_.y(), map_hi_.y()), ut(-M_PI, M_PI);
  Eigen::Vector2d p;
  for (int tries = 0; tries < 1000; ++tries) {
    p = Eigen::Vector2d(ux(rng_), uy(rng_));
    if (field_.At(p) >= config_.free_clearance_m) break;
  }
  return SE2(p.x(), p.y(), ut(rng_));
}

Estimate Mcl::Finish() { return std::move(estimate_); }

ModuleInfo MclModule() {
  return MakeModuleInfo<Mcl, MclConfig>(
      "mcl", "Monte Carlo localization in the known map: odometry sampling, likelihood field, low-variance resampling",
      {.odometry = true, .lidar = true, .map = true}, &BindParams);
}

}  // namespace slambox
