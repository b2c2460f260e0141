// The definitions of massprops/monte_carlo.h: Monte-Carlo and randomized quasi-Monte-Carlo mass
// properties of implicit solids, with a standard error on every output.

#include "massprops/monte_carlo.h"

#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

#include <Eigen/Eigenvalues>

#include "massprops/parallel.h"
#include "massprops/principal_axes.h"

namespace massprops {
namespace {

constexpr int kF = 10;  // integrands: 1, y1, y2, y3, y1², y2², y3², y1y2, y1y3, y2y3
constexpr int kC = kF * (kF + 1) / 2;
constexpr std::int64_t kBlock = 4096;
constexpr int kOutputs = 14;  // V, M, c(3), I xx yy zz xy xz yz, principal (3)

struct Sums {
  std::array<double, kF> s{};
  std::array<double, kC> c{};  // upper triangle of Σ f fᵀ (Monte Carlo only)
  Sums& operator+=(const Sums& o) {
    for (int i = 0; i < kF; ++i) s[static_cast<std::size_t>(i)] += o.s[static_cast<std::size_t>(i)];
    for (int i = 0; i < kC; ++i) c[static_cast<std::size_t>(i)] += o.c[static_cast<std::size_t>(i)];
    return *this;
  }
};

std::uint64_t SplitMix(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

double Uniform(std::uint64_t seed, std::uint64_t index, std::uint64_t dim) {
  const std::uint64_t h = SplitMix(SplitMix(seed ^ SplitMix(index)) + dim);
  return static_cast<double>(h >> 11) * 0x1.0p-53;
}

// Sobol direction numbers for the first three dimensions (Joe & Kuo): x, then the primitive
// polynomials x + 1 (m = 1) and x² + x + 1 (m = 1, 3).
struct SobolTable {
  std::array<std::array<std::uint32_t, 32>, 3> v{};
  SobolTable() {
    std::array<std::uint32_t, 32> m1{}, m2{};
    m1[0] = 1;
    for (int k = 1; k < 32; ++k) m1[k] = (2 * m1[k - 1]) ^ m1[k - 1];
    m2[0] = 1;
    m2[1] = 3;
    for (int k = 2; k < 32; ++k) m2[k] = (2 * m2[k - 1]) ^ (4 * m2[k - 2]) ^ m2[k - 2];
    for (int k = 0; k < 32; ++k) {
      v[0][k] = 1u << (31 - k);
      v[1][k] = m1[k] << (31 - k);
      v[2][k] = m2[k] << (31 - k);
    }
  }
};
const SobolTable& Sobol() {
  static const SobolTable table;
  return table;
}

std::uint32_t ReverseBits(std::uint32_t x) {
  x = ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
  x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
  x = ((x >> 4) & 0x0F0F0F0Fu) | ((x & 0x0F0F0F0Fu) << 4);
  x = ((x >> 8) & 0x00FF00FFu) | ((x & 0x00FF00FFu) << 8);
  return (x >> 16) | (x << 16);
}

// Nested uniform (Owen) scrambling by a hash that only mixes lower bits into higher ones, applied
// to the bit-reversed value (Burley, "Practical Hash-based Owen Scrambling", JCGT 2020).
std::uint32_t OwenScramble(std::uint32_t x, std::uint32_t seed) {
  x = ReverseBits(x);
  x += seed;
  x ^= x * 0x6c50b47cu;
  x ^= x * 0xb82f1e52u;
  x ^= x * 0xc7afe638u;
  x ^= x * 0x8d22f6e6u;
  return ReverseBits(x);
}

// Two-sided 95 % Student t quantiles for 1..30 degrees of freedom.
double StudentT95(int dof) {
  static const double kT[] = {12.706, 4.303, 3.182, 2.776, 2.571, 2.447, 2.365, 2.306, 2.262, 2.228,
                              2.201,  2.179, 2.160, 2.145, 2.131, 2.120, 2.110, 2.101, 2.093, 2.086,
                              2.080,  2.074, 2.069, 2.064, 2.060, 2.056, 2.052, 2.048, 2.045, 2.042};
  if (dof >= 1 && dof <= 30) return kT[dof - 1];
  return 1.959964 + 2.37 / dof;  // Cornish–Fisher, first term
}

void Accumulate(const ImplicitSolid& solid, const Vector3& c, const Vector3& h, const Vector3& u, bool cross,
                Sums& out) {
  const Vector3 y = 2.0 * u - Vector3::Ones();
  if (!solid.Inside(c + h.cwiseProduct(y))) return;
  const double f[kF] = {1.0,           y.x(),         y.y(),         y.z(),         y.x() * y.x(),
                        y.y() * y.y(), y.z() * y.z(), y.x() * y.y(), y.x() * y.z(), y.y() * y.z()};
  for (int i = 0; i < kF; ++i) out.s[static_cast<std::size_t>(i)] += f[i];
  if (cross) {
    int k = 0;
    for (int i = 0; i < kF; ++i) {
      for (int j = i; j < kF; ++j) out.c[static_cast<std::size_t>(k++)] += f[i] * f[j];
    }
  }
}

// Outputs from the means of the ten integrands (normalized coordinates y ∈ [−1, 1]³).
struct Frame {
  Vector3 c, h;
  double box_volume;
  double density;
  double fixed_mass;  // > 0: the density is mass / volume (so the mass carries no error)
};

std::array<double, kOutputs> Outputs(const std::array<double, kF>& mu, const Frame& fr,
                                     MassProperties* mp_out = nullptr, Vector3* principal = nullptr) {
  VolumeIntegrals vi;
  vi.reference = fr.c;
  vi.volume = fr.box_volume * mu[0];
  vi.first = fr.box_volume * fr.h.cwiseProduct(Vector3(mu[1], mu[2], mu[3]));
  Matrix3 yy;
  yy << mu[4], mu[7], mu[8], mu[7], mu[5], mu[9], mu[8], mu[9], mu[6];
  vi.second = fr.box_volume * (fr.h.asDiagonal() * yy * fr.h.asDiagonal());
  vi.surface_area = std::nan("");
  const MassProperties mp = FromIntegrals(vi, fr.fixed_mass > 0 ? fr.fixed_mass / vi.volume : fr.density);
  const Matrix3 sym = 0.5 * (mp.inertia_com + mp.inertia_com.transpose());
  Eigen::SelfAdjointEigenSolver<Matrix3> eig(sym, Eigen::EigenvaluesOnly);
  const Vector3 p = eig.eigenvalues();
  if (mp_out) *mp_out = mp;
  if (principal) *principal = p;
  const Matrix3& I = mp.inertia_com;
  return {mp.volume,
          mp.mass,
          mp.center_of_mass.x(),
          mp.center_of_mass.y(),
          mp.center_of_mass.z(),
          I(0, 0),
          I(1, 1),
          I(2, 2),
          I(0, 1),
          I(0, 2),
          I(1, 2),
          p[0],
          p[1],
          p[2]};
}

void Fill(MassPropertiesEstimate& e, const std::array<double, kOutputs>& se) {
  MassProperties& s = e.standard_error;
  s.volume = se[0];
  s.mass = se[1];
  s.center_of_mass = Vector3(se[2], se[3], se[4]);
  s.inertia_com << se[5], se[8], se[9], se[8], se[6], se[10], se[9], se[10], se[7];
  s.density = 0;
  s.surface_area = std::nan("");
  e.principal_moments_se = Vector3(se[11], se[12], se[13]);
}

}  // namespace

double MassPropertiesEstimate::MaxRelativeError() const {
  double r = standard_error.mass / std::abs(value.mass);
  for (int i = 0; i < 3; ++i) r = std::max(r, principal_moments_se[i] / std::abs(principal_moments[i]));
  return r;
}

bool MassPropertiesEstimate::MomentsIndistinct(int i) const {
  return principal_moments[i + 1] - principal_moments[i] < 3 * (principal_moments_se[i] + principal_moments_se[i + 1]);
}

namespace {

// The sums of block b (points [b kBlock, min(n, (b + 1) kBlock))) of randomization r: scrambled
// Sobol points for quasi-Monte Carlo, counter-based uniform ones for plain Monte Carlo.
Sums SumBlock(const ImplicitSolid& solid, const Frame& fr, const MonteCarloOptions& opt, bool qmc, std::size_t r,
              std::int64_t b, std::int64_t n) {
  Sums sums;
  const std::int64_t end = std::min(n, (b + 1) * kBlock);
  const std::uint64_t rseed = SplitMix(opt.seed * 0x2545F4914F6CDD1Dull + r);
  if (qmc) {
    // Sobol points in Gray-code order: within an aligned block of 2^k indices (and so for any
    // power-of-two count) the same set as natural order, one XOR per point.
    const auto& v = Sobol().v;
    std::uint32_t seeds[3], x[3];
    const auto i0 = static_cast<std::uint32_t>(b * kBlock);
    const std::uint32_t g0 = i0 ^ (i0 >> 1);
    for (int d = 0; d < 3; ++d) {
      seeds[d] = static_cast<std::uint32_t>(SplitMix(rseed * 3 + static_cast<std::uint64_t>(d)));
      x[d] = 0;
      for (int k = 0; k < 32; ++k) {
        if ((g0 >> k) & 1u) x[d] ^= v[static_cast<std::size_t>(d)][static_cast<std::size_t>(k)];
      }
    }
    for (std::int64_t i = b * kBlock; i < end; ++i) {
      if (i > b * kBlock) {
        const int k = __builtin_ctz(static_cast<std::uint32_t>(i));
        for (int d = 0; d < 3; ++d) x[d] ^= v[static_cast<std::size_t>(d)][static_cast<std::size_t>(k)];
      }
      const Vector3 u((static_cast<double>(OwenScramble(x[0], seeds[0])) + 0.5) * 0x1.0p-32,
                      (static_cast<double>(OwenScramble(x[1], seeds[1])) + 0.5) * 0x1.0p-32,
                      (static_cast<double>(OwenScramble(x[2], seeds[2])) + 0.5) * 0x1.0p-32);
      Accumulate(solid, fr.c, fr.h, u, false, sums);
    }
  } else {
    for (std::int64_t i = b * kBlock; i < end; ++i) {
      const auto idx = static_cast<std::uint64_t>(i);
      Accumulate(solid, fr.c, fr.h,
                 Vector3(Uniform(opt.seed, idx, 0), Uniform(opt.seed, idx, 1), Uniform(opt.seed, idx, 2)), true, sums);
    }
  }
  return sums;
}

// Plain Monte Carlo's standard errors by the delta method: Var(g(μ̂)) ≈ J Σ Jᵀ / N with Σ the
// covariance of the integrands.
std::array<double, kOutputs> DeltaMethodErrors(const Sums& pooled, const std::array<double, kF>& mu, const Frame& fr,
                                               std::int64_t samples) {
  const double N = static_cast<double>(samples);
  Eigen::Matrix<double, kF, kF> cov;
  int k = 0;
  for (int i = 0; i < kF; ++i) {
    for (int j = i; j < kF; ++j) {
      const double v = (pooled.c[static_cast<std::size_t>(k++)] / N -
                        mu[static_cast<std::size_t>(i)] * mu[static_cast<std::size_t>(j)]) *
                       N / (N - 1);
      cov(i, j) = cov(j, i) = v;
    }
  }
  Eigen::Matrix<double, kOutputs, kF> J;
  for (int i = 0; i < kF; ++i) {
    const double step = 1e-6 * std::max(std::abs(mu[static_cast<std::size_t>(i)]), 1e-3);
    auto up = mu, down = mu;
    up[static_cast<std::size_t>(i)] += step;
    down[static_cast<std::size_t>(i)] -= step;
    const auto a = Outputs(up, fr), b = Outputs(down, fr);
    for (int o = 0; o < kOutputs; ++o)
      J(o, i) = (a[static_cast<std::size_t>(o)] - b[static_cast<std::size_t>(o)]) / (2 * step);
  }
  const Eigen::Matrix<double, kOutputs, kOutputs> var = J * cov * J.transpose() / N;
  std::array<double, kOutputs> se{};
  for (int o = 0; o < kOutputs; ++o) se[static_cast<std::size_t>(o)] = std::sqrt(std::max(0.0, var(o, o)));
  return se;
}

}  // namespace

MassPropertiesEstimate EstimateMassProperties(const ImplicitSolid& solid, Scalar density,
                                              const MonteCarloOptions& opt) {
  if (!(std::isfinite(density) && density > 0))
    throw std::invalid_argument("Monte Carlo: the density must be finite and positive");
  if (opt.samples < 2) throw std::invalid_argument("Monte Carlo: at least 2 samples");
  const bool qmc = opt.method == SamplingMethod::kQuasiMonteCarlo;
  if (qmc && opt.randomizations < 2)
    throw std::invalid_argument("quasi-Monte Carlo: at least 2 randomizations (for the error bars)");
  if (!(opt.tolerance >= 0) || !std::isfinite(opt.tolerance))
    throw std::invalid_argument("Monte Carlo: the tolerance must be finite and >= 0");
  const AlignedBox3 box = solid.Bounds();
  const Vector3 size = box.sizes();
  if (box.isEmpty() || !(size.array() > 0).all() || !size.allFinite() || !box.min().allFinite()) {
    throw std::invalid_argument("Monte Carlo: the solid's bounding box is empty, flat or not finite");
  }
  if (!(opt.fixed_mass >= 0) || !std::isfinite(opt.fixed_mass))
    throw std::invalid_argument("Monte Carlo: the mass must be finite and positive");
  Frame fr{box.center(), 0.5 * size, size.prod(), density, opt.fixed_mass};
  const int R = qmc ? opt.randomizations : 1;
  // Points per randomization: QMC in powers of two (where the nets are balanced).
  std::int64_t n = std::max<std::int64_t>(1, (opt.samples + R - 1) / R);
  if (qmc) {
    std::int64_t p = 1;
    while (p < n) p *= 2;
    n = p;
    if (n > (std::int64_t{1} << 32))
      throw std::invalid_argument("quasi-Monte Carlo: more than 2^32 points per randomization");
  }
  std::vector<std::vector<Sums>> blocks(static_cast<std::size_t>(R));
  std::int64_t done = 0;  // points per randomization already summed
  MassPropertiesEstimate e;
  e.method = opt.method;
  e.seed = opt.seed;
  e.randomizations = R;
  while (true) {
    // Sum blocks [done, n) of every randomization.
    const std::int64_t first_block = done / kBlock;  // done is a multiple of kBlock or 0
    const std::int64_t nb = (n + kBlock - 1) / kBlock - first_block;
    for (auto& b : blocks) b.resize(static_cast<std::size_t>(first_block + nb));
    ParallelForBlocks(nb * R, opt.num_threads, [&](std::int64_t job) {
      const auto r = static_cast<std::size_t>(job / nb);
      const std::int64_t b = first_block + job % nb;
      blocks[r][static_cast<std::size_t>(b)] = SumBlock(solid, fr, opt, qmc, r, b, n);
    });
    done = n;
    e.samples = n * R;

    std::vector<Sums> per_r(static_cast<std::size_t>(R));
    Sums pooled;
    for (int r = 0; r < R; ++r) {
      std::vector<Sums> copy = blocks[static_cast<std::size_t>(r)];
      per_r[static_cast<std::size_t>(r)] = PairwiseSum(copy);
      pooled += per_r[static_cast<std::size_t>(r)];
    }
    if (pooled.s[0] == 0) {
      throw std::invalid_argument("Monte Carlo: none of the " + std::to_string(e.samples) +
                                  " points fell inside the solid (empty, or tiny within its bounding box)");
    }
    std::array<double, kF> mu{};
    for (int i = 0; i < kF; ++i)
      mu[static_cast<std::size_t>(i)] = pooled.s[static_cast<std::size_t>(i)] / static_cast<double>(e.samples);
    Outputs(mu, fr, &e.value, &e.principal_moments);
    std::array<double, kOutputs> se{};
    if (qmc) {
      // Spread of the R independent estimates.
      std::vector<std::array<double, kOutputs>> est;
      std::array<double, kOutputs> mean{};
      for (int r = 0; r < R; ++r) {
        std::array<double, kF> m{};
        for (int i = 0; i < kF; ++i)
          m[static_cast<std::size_t>(i)] =
              per_r[static_cast<std::size_t>(r)].s[static_cast<std::size_t>(i)] / static_cast<double>(n);
        if (m[0] == 0)
          throw std::invalid_argument(
              "quasi-Monte Carlo: a randomization had no point inside the solid; use more samples");
        est.push_back(Outputs(m, fr));
        for (int k = 0; k < kOutputs; ++k)
          mean[static_cast<std::size_t>(k)] += est.back()[static_cast<std::size_t>(k)] / R;
      }
      for (int k = 0; k < kOutputs; ++k) {
        double ss = 0;
        for (const auto& x : est)
          ss += (x[static_cast<std::size_t>(k)] - mean[static_cast<std::size_t>(k)]) *
                (x[static_cast<std::size_t>(k)] - mean[static_cast<std::size_t>(k)]);
        se[static_cast<std::size_t>(k)] = std::sqrt(ss / (R - 1) / R);
      }
      e.interval95_factor = StudentT95(R - 1);
    } else {
      se = DeltaMethodErrors(pooled, mu, fr, e.samples);
      e.interval95_factor = 1.959964;
    }
    Fill(e, se);
    if (opt.tolerance <= 0) break;
    e.tolerance_met = e.MaxRelativeError() < opt.tolerance;
    if (e.tolerance_met || 2 * n * R > opt.max_samples || (qmc && 2 * n > (std::int64_t{1} << 32))) break;
    // Keep whole blocks so that a longer run reuses the shorter one's sums exactly.
    n = std::max(2 * n, kBlock);
  }
  return e;
}

}  // namespace massprops
