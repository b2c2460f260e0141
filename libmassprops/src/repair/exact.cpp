// Certified mass properties (exact.h): exact integer sums with GMP, exact rationals, MPFR for the
// one correct rounding, a Sturm sequence for the principal moments.

#include "massprops/repair/exact.h"

#include <gmp.h>
#include <gmpxx.h>
#include <mpfr.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <stdexcept>
#include <tuple>
#include <vector>

#include <Eigen/Eigenvalues>

#include "massprops/parallel.h"

namespace massprops {
namespace {

using Rat = mpq_class;

Rat RatOf(double x) {
  Rat q;
  mpq_set_d(q.get_mpq_t(), x);  // exact: a double is a dyadic rational
  return q;
}

double Rounded(const Rat& q, mpfr_rnd_t mode = MPFR_RNDN) {
  mpfr_t f;
  mpfr_init2(f, 53);
  mpfr_set_q(f, q.get_mpq_t(), mode);  // one correct rounding to 53 bits
  const double d = mpfr_get_d(f, mode);
  mpfr_clear(f);
  return d;
}

// The library's units as the exact decimals they are defined as.
Rat UnitRational(double metres_per_unit) {
  const std::pair<double, Rat> table[] = {
      {1.0, Rat(1)},           {0.01, Rat(1, 100)},       {0.001, Rat(1, 1000)},
      {1e-6, Rat(1, 1000000)}, {0.0254, Rat(254, 10000)}, {0.3048, Rat(3048, 10000)}};
  for (const auto& [d, q] : table) {
    if (d == metres_per_unit) {
      Rat r = q;
      r.canonicalize();
      return r;
    }
  }
  throw std::invalid_argument("exact integration takes the units of the table (m, cm, mm, um, in, ft)");
}

// Sums over triangles of det, det·s_i and det·(a_i a_j + b_i b_j + c_i c_j + s_i s_j) in integers.
struct Sums {
  mpz_class v6, f[3], s[6];
  Sums& operator+=(const Sums& o) {
    v6 += o.v6;
    for (int i = 0; i < 3; ++i) f[i] += o.f[i];
    for (int k = 0; k < 6; ++k) s[k] += o.s[k];
    return *this;
  }
};

constexpr int kPairs[6][2] = {{0, 0}, {1, 1}, {2, 2}, {0, 1}, {0, 2}, {1, 2}};

// A polynomial with rational coefficients, lowest degree first.
using Poly = std::vector<Rat>;

Rat Eval(const Poly& p, const Rat& x) {
  Rat y = 0;
  for (auto it = p.rbegin(); it != p.rend(); ++it) y = y * x + *it;
  return y;
}

Poly Remainder(Poly a, const Poly& b) {
  while (a.size() >= b.size() && !a.empty()) {
    const Rat k = a.back() / b.back();
    const std::size_t shift = a.size() - b.size();
    for (std::size_t i = 0; i < b.size(); ++i) a[shift + i] -= k * b[i];
    a.pop_back();
    while (!a.empty() && a.back() == 0) a.pop_back();
  }
  return a;
}

// Sign changes of the Sturm sequence at x.
int SignChanges(const std::vector<Poly>& sturm, const Rat& x) {
  int changes = 0, last = 0;
  for (const Poly& p : sturm) {
    const int s = sgn(Eval(p, x));
    if (s == 0) continue;
    if (last != 0 && s != last) ++changes;
    last = s;
  }
  return changes;
}

// The exact integer sums over the triangles (6 V, 24 F, 120 S in integer steps) of the mesh's
// coordinates scaled to integers by 2^-e_min (every coordinate is M·2^e with an integer M of at
// most 53 bits); `e_min` is set.
Sums ExactSums(const TriangleMesh& mesh, int num_threads, int& e_min) {
  e_min = INT_MAX;
  for (Eigen::Index i = 0; i < mesh.V.size(); ++i) {
    const double x = mesh.V.data()[i];
    if (!std::isfinite(x)) throw std::invalid_argument("a coordinate is not finite");
    if (x == 0) continue;
    int e = 0;
    std::frexp(x, &e);
    e_min = std::min(e_min, e - 53);
  }
  if (e_min == INT_MAX) throw std::invalid_argument("every coordinate is zero: no volume");
  std::vector<mpz_class> X(static_cast<std::size_t>(mesh.V.size()));
  for (std::size_t i = 0; i < X.size(); ++i) {
    int e = 0;
    const double f = std::frexp(mesh.V.data()[i], &e);
    X[i] = static_cast<long>(std::ldexp(f, 53));  // exact: the 53-bit mantissa
    mpz_mul_2exp(X[i].get_mpz_t(), X[i].get_mpz_t(), static_cast<mp_bitcnt_t>(e - 53 - e_min));
  }
  // Exact sums, in blocks on threads (an exact sum does not depend on the order).
  const std::int64_t nt = mesh.F.rows();
  constexpr std::int64_t kBlock = 8192;
  const std::int64_t blocks = (nt + kBlock - 1) / kBlock;
  std::vector<Sums> parts(static_cast<std::size_t>(std::max<std::int64_t>(blocks, 1)));
  ParallelForBlocks(blocks, num_threads, [&](std::int64_t b) {
    Sums& acc = parts[static_cast<std::size_t>(b)];
    mpz_class t[3], det, s[3], q;
    for (std::int64_t k = b * kBlock; k < std::min(nt, (b + 1) * kBlock); ++k) {
      const mpz_class* a = &X[3 * static_cast<std::size_t>(mesh.F(k, 0))];
      const mpz_class* bb = &X[3 * static_cast<std::size_t>(mesh.F(k, 1))];
      const mpz_class* c = &X[3 * static_cast<std::size_t>(mesh.F(k, 2))];
      mpz_mul(t[0].get_mpz_t(), bb[1].get_mpz_t(), c[2].get_mpz_t());
      mpz_submul(t[0].get_mpz_t(), bb[2].get_mpz_t(), c[1].get_mpz_t());
      mpz_mul(t[1].get_mpz_t(), bb[2].get_mpz_t(), c[0].get_mpz_t());
      mpz_submul(t[1].get_mpz_t(), bb[0].get_mpz_t(), c[2].get_mpz_t());
      mpz_mul(t[2].get_mpz_t(), bb[0].get_mpz_t(), c[1].get_mpz_t());
      mpz_submul(t[2].get_mpz_t(), bb[1].get_mpz_t(), c[0].get_mpz_t());
      mpz_mul(det.get_mpz_t(), a[0].get_mpz_t(), t[0].get_mpz_t());
      mpz_addmul(det.get_mpz_t(), a[1].get_mpz_t(), t[1].get_mpz_t());
      mpz_addmul(det.get_mpz_t(), a[2].get_mpz_t(), t[2].get_mpz_t());
      acc.v6 += det;
      for (int i = 0; i < 3; ++i) {
        mpz_add(s[i].get_mpz_t(), a[i].get_mpz_t(), bb[i].get_mpz_t());
        mpz_add(s[i].get_mpz_t(), s[i].get_mpz_t(), c[i].get_mpz_t());
        mpz_addmul(acc.f[i].get_mpz_t(), det.get_mpz_t(), s[i].get_mpz_t());
      }
      for (int p = 0; p < 6; ++p) {
        const int i = kPairs[p][0], j = kPairs[p][1];
        mpz_mul(q.get_mpz_t(), a[i].get_mpz_t(), a[j].get_mpz_t());
        mpz_addmul(q.get_mpz_t(), bb[i].get_mpz_t(), bb[j].get_mpz_t());
        mpz_addmul(q.get_mpz_t(), c[i].get_mpz_t(), c[j].get_mpz_t());
        mpz_addmul(q.get_mpz_t(), s[i].get_mpz_t(), s[j].get_mpz_t());
        mpz_addmul(acc.s[p].get_mpz_t(), det.get_mpz_t(), q.get_mpz_t());
      }
    }
  });
  Sums sum;
  for (const Sums& p : parts) sum += p;

  return sum;
}

}  // namespace

ExactMassProperties ExactMassPropertiesOf(const PolygonMesh& polygons, double metres_per_unit, const MassSpec& mass,
                                          int num_threads) {
  const Rat unit = UnitRational(metres_per_unit);
  const TriangleMesh mesh = Triangulate(polygons);
  int e_min = 0;
  const Sums sum = ExactSums(mesh, num_threads, e_min);

  // Rationals: the length of one integer step in metres is L = 2^e_min · unit.
  Rat L = unit;
  if (e_min >= 0) {
    mpq_mul_2exp(L.get_mpq_t(), L.get_mpq_t(), static_cast<mp_bitcnt_t>(e_min));
  } else {
    mpq_div_2exp(L.get_mpq_t(), L.get_mpq_t(), static_cast<mp_bitcnt_t>(-e_min));
  }
  const Rat L3 = L * L * L, L4 = L3 * L, L5 = L4 * L;
  const Rat V = Rat(sum.v6) / 6 * L3;
  if (sgn(V) <= 0) throw std::invalid_argument("the exact volume is not positive");
  Rat F[3], S[3][3];
  for (int i = 0; i < 3; ++i) F[i] = Rat(sum.f[i]) / 24 * L4;
  for (int p = 0; p < 6; ++p) {
    const int i = kPairs[p][0], j = kPairs[p][1];
    S[i][j] = S[j][i] = Rat(sum.s[p]) / 120 * L5;
  }
  const Rat rho = FixesMass(mass) ? RatOf(std::get<TotalMass>(mass).value) / V : RatOf(std::get<Density>(mass).value);
  // About the center of mass c = F / V: S_c = S − F Fᵀ / V; I = ρ (tr(S_c) E − S_c).
  Rat Sc[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) Sc[i][j] = S[i][j] - F[i] * F[j] / V;
  const Rat trace = Sc[0][0] + Sc[1][1] + Sc[2][2];
  Rat I[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) I[i][j] = rho * ((i == j ? trace : Rat(0)) - Sc[i][j]);

  ExactMassProperties out;
  out.mp.volume = Rounded(V);
  out.mp.mass = Rounded(rho * V);
  out.mp.density = Rounded(rho);
  for (int i = 0; i < 3; ++i) {
    out.mp.center_of_mass[i] = Rounded(F[i] / V);
    for (int j = 0; j < 3; ++j) out.mp.inertia_com(i, j) = Rounded(I[i][j]);
  }

  // Principal moments: the roots of det(λE − I) = λ³ − t λ² + m λ − d, isolated by a Sturm
  // sequence and bisected on doubles until the enclosures are a few ulps wide.
  const Rat t = trace * rho * 2;  // tr(I) = ρ(3 tr S_c − tr S_c) = 2ρ tr S_c
  const Rat m = I[0][0] * I[1][1] - I[0][1] * I[0][1] + I[0][0] * I[2][2] - I[0][2] * I[0][2] + I[1][1] * I[2][2] -
                I[1][2] * I[1][2];
  const Rat d = I[0][0] * (I[1][1] * I[2][2] - I[1][2] * I[1][2]) - I[0][1] * (I[0][1] * I[2][2] - I[1][2] * I[0][2]) +
                I[0][2] * (I[0][1] * I[1][2] - I[1][1] * I[0][2]);
  std::vector<Poly> sturm{{-d, m, -t, Rat(1)}, {m, -2 * t, Rat(3)}};
  while (true) {
    Poly r = Remainder(sturm[sturm.size() - 2], sturm.back());
    if (r.empty()) break;
    for (Rat& c : r) c = -c;
    sturm.push_back(r);
  }
  Rat bound = 1;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) bound += abs(I[i][j]);
  const double hi0 = Rounded(bound, MPFR_RNDU), lo0 = -hi0;  // every eigenvalue lies within
  auto changes = [&](double x) { return SignChanges(sturm, RatOf(x)); };
  auto not_a_root = [&](double x, double toward) {
    while (x != toward && sgn(Eval(sturm[0], RatOf(x))) == 0) x = std::nextafter(x, toward);
    return x;
  };
  std::vector<std::pair<double, double>> roots;
  // Roots in (lo, hi], `count` of them.
  std::vector<std::tuple<double, double, int>> work{{lo0, hi0, changes(lo0) - changes(hi0)}};
  while (!work.empty()) {
    auto [lo, hi, count] = work.back();
    work.pop_back();
    if (count == 0) continue;
    const double mid = not_a_root(lo + (hi - lo) / 2, hi);
    const double width = hi - lo;
    if (mid <= lo || mid >= hi ||
        (count == 1 && width <= 4 * std::nextafter(std::abs(hi), INFINITY) - 4 * std::abs(hi))) {
      roots.emplace_back(lo, hi);
      continue;
    }
    const int left = changes(lo) - changes(mid);
    work.emplace_back(mid, hi, count - left);
    work.emplace_back(lo, mid, left);
  }
  std::sort(roots.begin(), roots.end());
  out.distinct_moments = static_cast<int>(roots.size());
  // Each of the three moments (ascending, with multiplicity) takes the enclosure nearest its
  // double-precision value.
  Eigen::SelfAdjointEigenSolver<Matrix3> eig(out.mp.inertia_com, Eigen::EigenvaluesOnly);
  for (int k = 0; k < 3; ++k) {
    const double approx = eig.eigenvalues()[k];
    std::size_t best = 0;
    for (std::size_t r = 1; r < roots.size(); ++r) {
      const auto gap = [&](std::size_t s) {
        return approx < roots[s].first    ? roots[s].first - approx
               : approx > roots[s].second ? approx - roots[s].second
                                          : 0.0;
      };
      if (gap(r) < gap(best)) best = r;
    }
    out.moments[static_cast<std::size_t>(k)] = roots.empty() ? std::make_pair(approx, approx) : roots[best];
  }
  return out;
}

}  // namespace massprops
