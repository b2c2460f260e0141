// The Gauss–Seidel kernels of the velocity solve: a row's normal update, a patch's normals as one
// block, its friction (Coulomb's cone with torsion), a sweep, and shock propagation
// (solver_internal.h).

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include <Eigen/Cholesky>

#include "../integrators/integrator.h"
#include "solver_internal.h"
#include "workers.h"

namespace dynamics::contact {
namespace {

// One Gauss–Seidel update of a row's normal impulse: the least that keeps its normal velocity
// at its target.
void UpdateNormal(Row& r, std::vector<Velocities>& vel, int frozen, double mass_n, Progress& progress) {
  const double vn = NormalSpeed(vel, r);
  const double ln = std::max(r.lambda_n + mass_n * (r.target - vn), 0.0);
  const double dn = ln - r.lambda_n;
  r.lambda_n = ln;
  ApplyNormal(vel, r, dn, frozen);
  progress.change = std::max(progress.change, std::abs(dn));
  progress.scale = std::max(progress.scale, ln);
  progress.speed = std::max(progress.speed, std::abs(dn) / mass_n);
}

// Moves a sliding patch's anchor to the centre of pressure of its rows' present normal impulses
// (kinetic friction so acts where the load is, as friction distributed over the points would: a
// sliding box does not yaw because its points are unevenly spread), carrying the friction impulse
// already applied along: off where it was, on where it now is. (A holding patch with three or
// more points holds the body whatever its anchor.)
void FollowPressure(Patch& p, std::vector<Velocities>& vel, const BodyResponse& bodies, int frozen, Vector3 centre) {
  centre += p.n * p.n.dot(p.anchor - centre);                                               // in the patch's plane
  if ((centre - p.anchor).squaredNorm() <= std::max(1e-24, 1e-16 * p.rho * p.rho)) return;  // within 10⁻⁸ ρ
  ApplyPatch(vel, p, -p.lambda, frozen);
  p.ra += centre - p.anchor;
  if (p.b >= 0) p.rb += centre - p.anchor;
  p.anchor = centre;
  SetPatchJacobian(p, bodies);
  ApplyPatch(vel, p, p.lambda, frozen);
}

// The impulse nearest `target` in the metric of the response K (the one that leaves the least
// kinetic energy) within the ball |λ| ≤ bound, over the first `dim` components: Coulomb's
// maximal dissipation, the friction then opposing the patch's sliding at the end of the update.
// On the ball's surface λ(ν) = (K + ν E)⁻¹ K target with ν ≥ 0 such that |λ| = bound (a
// trust-region step: Newton on 1/|λ(ν)| − 1/bound, which is nearly linear in ν).
Vector3 ProjectOntoBall(const Matrix3& K, const Vector3& target, double bound, int dim, double& nu_guess) {
  if (!(bound > 0)) return Vector3::Zero();
  Matrix3 Kd = K;
  if (dim == 2) {
    Kd.row(2).setZero();
    Kd.col(2).setZero();
    Kd(2, 2) = 1;
  }
  const Vector3 Kt = Kd * target;
  // x(ν) = (K + ν E)⁻¹ K t as polynomials in ν (Cayley–Hamilton: adj(K + ν E) = adj K +
  // ν (tr K E − K) + ν² E, and adj K · K = det K · E): x = N(ν) / D(ν) with N = det K t +
  // ν (tr K · Kt − K Kt) + ν² Kt and D = det(K + ν E) = ν³ + tr K ν² + c₂ ν + det K (c₂ the sum of
  // K's principal 2 × 2 minors). An iteration is then a few products, not a 3 × 3 inverse.
  const double tr = Kd.trace(), det = Kd.determinant();
  const double c2 = Kd(0, 0) * Kd(1, 1) - Kd(0, 1) * Kd(1, 0) + Kd(0, 0) * Kd(2, 2) - Kd(0, 2) * Kd(2, 0) +
                    Kd(1, 1) * Kd(2, 2) - Kd(1, 2) * Kd(2, 1);
  const Vector3 a0 = det * target, a1 = tr * Kt - Kd * Kt, a2 = Kt;
  // x, |x| and d|x|²/dν = 2 (N·N' D − |N|² D') / D³.
  auto at = [&](double nu, Vector3& x, double& length, double& slope) {
    const Vector3 N = a0 + nu * (a1 + nu * a2), dN = a1 + 2 * nu * a2;
    const double D = ((nu + tr) * nu + c2) * nu + det, dD = (3 * nu + 2 * tr) * nu + c2;
    x = N / D;
    length = N.norm() / D;
    slope = 2 * (N.dot(dN) * D - N.squaredNorm() * dD) / (D * D * D);
  };
  // Newton on φ(ν) = 1/|x| − 1/bound, φ' = −½ |x|⁻³ d|x|²/dν: nearly linear and concave, so from
  // below the root it approaches monotonically, and from above it lands below it. Started from
  // the ν of the patch's last projection (the sweeps change it little), else from 0 (x = t).
  double nu = nu_guess > 0 && std::isfinite(nu_guess) ? nu_guess : 0.0, length = 0, slope = 0;
  Vector3 x;
  at(nu, x, length, slope);
  for (int k = 0; k < 50; ++k) {
    const double phi = 1 / length - 1 / bound, dphi = -0.5 * slope / (length * length * length);
    if (std::abs(phi) * bound <= 1e-12 || !(dphi > 0) || !std::isfinite(dphi)) break;
    const double next = nu - phi / dphi;
    nu = next > 0 ? next : nu * 1e-3;  // (ν ≥ 0: below 0 the ball holds x(0) = t already)
    at(nu, x, length, slope);
  }
  nu_guess = nu;
  if (!(length <= bound)) x *= bound / length;  // the last rounding (or a direction without response)
  if (dim == 2) x[2] = 0;
  return x;
}

// One update of a patch's friction: the impulse that stops its sliding and turning, if it lies
// within the limit μ N (the patch holds, or comes to rest in this step); else the impulse of
// least kinetic energy on the limit (μs: a holding patch breaks away; μk: a sliding one slides,
// opposing its sliding). With a body held still (shock propagation), only the other's response
// counts.
void UpdateFriction(Patch& p, const std::vector<Row>& rows, std::vector<Velocities>& vel, const BodyResponse& bodies,
                    int frozen, Progress& progress) {
  const bool follow = p.sliding && frozen < 0;
  Vector3 centre = p.anchor;
  const double N = Load(p, rows, follow ? &centre : nullptr);
  if (follow && N > 0) FollowPressure(p, vel, bodies, frozen, centre);
  const Matrix3 mass = frozen < 0 ? p.mass : PatchMass(frozen == p.a ? p.Kb : p.Ka, p.rho);
  const Matrix3 K = frozen < 0 ? Matrix3(p.Ka + p.Kb) : (frozen == p.a ? p.Kb : p.Ka);
  const Vector3 lt = FrictionUpdate(p, p.lambda, PatchVelocity(vel, p), mass, K, p.mu * N);
  const Vector3 d = lt - p.lambda;
  p.lambda = lt;
  ApplyPatch(vel, p, d, frozen);
  progress.change = std::max(progress.change, d.norm());
  progress.scale = std::max(progress.scale, lt.norm());
  progress.speed = std::max(progress.speed, (K * d).norm());
}

// A patch's normal impulses (2 to 4 points) solved together: the new impulses x ≥ 0 whose normal
// velocities w = A x − c reach their targets (w ≥ 0), complementary (x·w = 0), with A the points'
// coupled response — the linear complementarity problem of the patch alone, by trying the sets of
// loaded points, the most first. Four coplanar points make A singular (a rigid face's load is
// shared in infinitely many ways): a regularization of 10⁻⁹ of its diagonal picks the evenest
// sharing and misses each target by 10⁻⁹ of the change (of jointed bodies, it regularizes the
// change: the sharing is kept, the targets met). Returns false where no set solves it (rounding),
// for the point-by-point update.
bool UpdateNormalBlock(Patch& p, std::vector<Row>& rows, std::vector<Velocities>& vel, Progress& progress) {
  const int m = p.count;
  if (m < 2 || m > 4) return false;
  const Eigen::Matrix4d& A = p.block;
  Eigen::Vector4d c = Eigen::Vector4d::Zero(), old = Eigen::Vector4d::Zero();
  Row* r = &rows[static_cast<std::size_t>(p.first)];
  for (int i = 0; i < m; ++i) old[i] = r[i].lambda_n;
  for (int i = 0; i < m; ++i) {
    c[i] = r[i].target - NormalSpeed(vel, r[i]) + A.row(i).head(m).dot(old.head(m));
  }
  const double scale = c.head(m).cwiseAbs().maxCoeff();
  // Jointed bodies: the regularization acts on the change, as in the block solve
  // (block_solve.cpp): where the load's sharing is not determined it is kept, and the fixed point
  // is the unregularized one, which both then share.
  const bool proximal = p.coupling != nullptr;
  Eigen::Vector4d x = Eigen::Vector4d::Zero();
  // One set of loaded points: their impulses solve their block (Cholesky, the regularization on
  // its diagonal), none negative, and the others' velocities reach their targets unloaded.
  auto try_set = [&](int set) {
    int index[4], k = 0;
    for (int i = 0; i < m; ++i) {
      if (set & (1 << i)) index[k++] = i;
    }
    double(&L)[4][4] = p.factor;
    if (p.factored != set) {
      p.factored = set;
      p.factor_ok = false;
      for (int i = 0; i < k; ++i) {
        for (int j = 0; j <= i; ++j) {
          double sum = A(index[i], index[j]) * (i == j ? 1 + 1e-9 : 1.0);
          for (int l = 0; l < j; ++l) sum -= L[i][l] * L[j][l];
          if (i == j) {
            if (!(sum > 0)) return false;  // singular beyond the regularization
            L[i][i] = std::sqrt(sum);
          } else {
            L[i][j] = sum / L[j][j];
          }
        }
      }
      p.factor_ok = true;
    }
    if (!p.factor_ok) return false;
    double y[4] = {};
    for (int i = 0; i < k; ++i) {
      double sum = c[index[i]];
      if (proximal) {
        for (int j = 0; j < k; ++j) sum -= A(index[i], index[j]) * old[index[j]];
      }
      for (int l = 0; l < i; ++l) sum -= L[i][l] * y[l];
      y[i] = sum / L[i][i];
    }
    double solved[4] = {};
    for (int i = k - 1; i >= 0; --i) {
      double sum = y[i];
      for (int l = i + 1; l < k; ++l) sum -= L[l][i] * solved[l];
      solved[i] = sum / L[i][i];
    }
    Eigen::Vector4d trial = Eigen::Vector4d::Zero();
    for (int i = 0; i < k; ++i) {
      trial[index[i]] = solved[i] + (proximal ? old[index[i]] : 0.0);
      if (!(trial[index[i]] >= 0)) return false;
    }
    for (int i = 0; i < m; ++i) {
      if (!(set & (1 << i)) && !(A.row(i).head(m).dot(trial.head(m)) - c[i] >= -1e-9 * scale)) return false;
    }
    x = trial;
    return true;
  };
  // The points loaded now first (the set rarely changes from sweep to sweep), then every set, the
  // most points first.
  static constexpr int kBySize[] = {15, 14, 13, 11, 7, 12, 10, 9, 6, 5, 3, 8, 4, 2, 1, 0};
  int loaded = 0;
  for (int i = 0; i < m; ++i) loaded |= old[i] > 0 ? 1 << i : 0;
  bool solved = loaded != 0 && try_set(loaded);
  for (const int set : kBySize) {
    if (solved) break;
    if (set >> m == 0 && (loaded == 0 || set != loaded)) solved = try_set(set);
  }
  if (!solved) return false;
  const Eigen::Vector4d d = x - old;
  const Eigen::Vector4d dv = A * d;
  for (int i = 0; i < m; ++i) {
    ApplyNormal(vel, r[i], d[i], -1);
    r[i].lambda_n = x[i];
    progress.change = std::max(progress.change, std::abs(d[i]));
    progress.scale = std::max(progress.scale, x[i]);
    progress.speed = std::max(progress.speed, std::abs(dv[i]));
  }
  return true;
}

// A holding patch of free bodies solved whole: its normal impulses and its friction together,
// as the one linear system of its loaded points and its sticking (each loaded point's normal
// velocity at its target, the patch's sliding and turning stopped), with the other patches'
// impulses as they are. Accepted only when it is the patch's answer — every loaded point still
// pushes, every other one separates, the friction lies within μ N — which the alternating normal
// and friction updates below converge to; here it takes one update. The system's factor is kept
// between sweeps (the loaded set rarely changes). False, with nothing changed, otherwise: a patch
// that slides, breaks away or lifts a point, or acts through jointed bodies.
bool UpdatePatchJointly(Patch& p, std::vector<Row>& rows, std::vector<Velocities>& vel, Progress& progress) {
  const int m = p.count;
  if (m < 1 || m > 4 || p.sliding || p.coupling != nullptr || !(p.mu > 0)) return false;
  Row* r = &rows[static_cast<std::size_t>(p.first)];
  int set = 0, index[4], k = 0;
  for (int i = 0; i < m; ++i) {
    if (r[i].a != p.a || r[i].b != p.b) return false;
    if (r[i].lambda_n > 0) {
      set |= 1 << i;
      index[k++] = i;
    }
  }
  if (k == 0) return false;
  const int nf = p.rho > 0 ? 3 : 2, size = k + nf;
  using Matrix7 = Eigen::Matrix<double, 7, 7>;
  using Vector7 = Eigen::Matrix<double, 7, 1>;
  // Row i of the patch's normals against its friction: the normal velocity at point i per unit
  // friction impulse (and, by symmetry, the friction's velocity per unit normal impulse at i).
  const double inv_mass = p.inv_mass_a + p.inv_mass_b;
  auto coupling = [&](int i, int f) {
    double x = r[i].ang_a.dot(p.turn_a.col(f)) + r[i].ang_b.dot(p.turn_b.col(f));
    if (f < 2) x += inv_mass * r[i].n.dot(f == 0 ? p.t1 : p.t2);
    return x;
  };
  if (p.joint_set != set) {
    p.joint_set = set;
    Matrix7 A = Matrix7::Identity();  // the unused rows and columns: a fixed size, no allocation
    for (int i = 0; i < k; ++i) {
      for (int j = 0; j < k; ++j) A(i, j) = m == 1 ? 1 / r[0].mass_n : p.block(index[i], index[j]);
      A(i, i) *= 1 + 1e-9;  // four coplanar points: the evenest sharing of the load
      for (int f = 0; f < nf; ++f) A(i, k + f) = A(k + f, i) = coupling(index[i], f);
    }
    const Matrix3 K = p.Ka + p.Kb;
    A.block(k, k, nf, nf) = K.topLeftCorner(nf, nf);
    const Eigen::LLT<Matrix7> llt(A);
    p.joint_ok = llt.info() == Eigen::Success;
    p.joint = llt.matrixLLT();
  }
  if (!p.joint_ok) return false;
  Vector7 c = Vector7::Zero();
  for (int i = 0; i < k; ++i) c[i] = r[index[i]].target - NormalSpeed(vel, r[index[i]]);
  const Vector3 g = PatchVelocity(vel, p);
  for (int f = 0; f < nf; ++f) c[k + f] = -g[f];
  Vector7 d = p.joint.triangularView<Eigen::Lower>().solve(c);
  p.joint.triangularView<Eigen::Lower>().transpose().solveInPlace(d);
  if (!d.allFinite()) return false;
  double N = 0;
  for (int i = 0; i < k; ++i) {
    const double ln = r[index[i]].lambda_n + d[i];
    if (!(ln >= 0)) return false;
    N += ln;
  }
  Vector3 lt = p.lambda;
  for (int f = 0; f < nf; ++f) lt[f] += d[k + f];
  if (!(lt.norm() <= p.mu * N)) return false;
  // The unloaded points separate (their normal velocity after the update at its target or above).
  double scale = c.head(size).cwiseAbs().maxCoeff();
  for (int i = 0; i < m; ++i) {
    if (set & (1 << i)) continue;
    double w = NormalSpeed(vel, r[i]) - r[i].target;
    for (int j = 0; j < k; ++j) w += (m == 1 ? 0.0 : p.block(i, index[j])) * d[j];
    for (int f = 0; f < nf; ++f) w += coupling(i, f) * d[k + f];
    if (!(w >= -1e-9 * scale)) return false;
  }
  for (int i = 0; i < k; ++i) {
    Row& row = r[index[i]];
    ApplyNormal(vel, row, d[i], -1);
    row.lambda_n += d[i];
    progress.change = std::max(progress.change, std::abs(d[i]));
    progress.scale = std::max(progress.scale, row.lambda_n);
  }
  const Vector3 df = lt - p.lambda;
  p.lambda = lt;
  ApplyPatch(vel, p, df, -1);
  progress.change = std::max(progress.change, df.norm());
  progress.scale = std::max(progress.scale, lt.norm());
  // The velocity change at the loaded points and of the sliding: c, the residual before.
  progress.speed = std::max(progress.speed, c.head(k).cwiseAbs().maxCoeff());
  progress.speed = std::max(progress.speed, c.segment(k, nf).norm());
  return true;
}

}  // namespace

// Coulomb's friction update (solver_internal.h): the impulse that stops the sliding, if within
// the limit; else the one of least kinetic energy on it.
Vector3 FrictionUpdate(Patch& p, const Vector3& old, const Vector3& g, const Matrix3& mass, const Matrix3& K,
                       double bound) {
  const Vector3 stop = old - mass * g;
  if (!(stop.norm() > bound)) return stop;
  return ProjectOntoBall(K, stop, bound, p.rho > 0 ? 3 : 2, p.nu);
}

// A patch's total normal impulse N, and (when `centre` is given) its centre of pressure
// Σ λn x / N (left as it is when N = 0).
double Load(const Patch& p, const std::vector<Row>& rows, Vector3* centre) {
  double N = 0;
  Vector3 weighted = Vector3::Zero();
  for (int i = p.first; i < p.first + p.count; ++i) {
    const Row& r = rows[static_cast<std::size_t>(i)];
    N += r.lambda_n;
    if (centre != nullptr) weighted += r.lambda_n * r.point;
  }
  if (centre != nullptr && N > 0) *centre = weighted / N;
  return N;
}

// A sweep over the patches in `order` (forward or backward): each patch's normals (together, by
// default; point by point in exact mode, as rbsim 0.3), then its friction.
void Sweep(std::vector<Row>& rows, std::vector<Patch>& patches, const std::vector<int>& order, bool forward, bool block,
           std::vector<Velocities>& vel, const BodyResponse& bodies, Progress& progress) {
  const int n = static_cast<int>(order.size());
  for (int k = 0; k < n; ++k) {
    Patch& p = patches[static_cast<std::size_t>(order[static_cast<std::size_t>(forward ? k : n - 1 - k)])];
    SweepPatch(p, rows, forward, block, n == 1, vel, bodies, progress);
  }
}

void SweepPatch(Patch& p, std::vector<Row>& rows, bool forward, bool block, bool alone, std::vector<Velocities>& vel,
                const BodyResponse& bodies, Progress& progress) {
  if (block && alone && UpdatePatchJointly(p, rows, vel, progress)) return;
  if (block && UpdateNormalBlock(p, rows, vel, progress)) {
    UpdateFriction(p, rows, vel, bodies, -1, progress);
    return;
  }
  for (int j = 0; j < p.count; ++j) {
    Row& r = rows[static_cast<std::size_t>(forward ? p.first + j : p.first + p.count - 1 - j)];
    UpdateNormal(r, vel, -1, r.mass_n, progress);
  }
  UpdateFriction(p, rows, vel, bodies, -1, progress);
}

// Shock propagation (Guendelman, Bridson & Fedkiw 2003): level by level from the ground up, each
// body's contacts with the level below are solved with the lower body held still, so what the
// iterations left of a resting stack's velocities does not survive the step.
void PropagateShock(std::vector<Row>& rows, std::vector<Patch>& patches, const std::vector<int>& order,
                    std::vector<Velocities>& vel, const BodyResponse& bodies, const std::vector<int>& body_level,
                    const SolveSettings& settings) {
  constexpr int kNone = std::numeric_limits<int>::max();
  int max_level = -1;
  for (const int k : order) {
    const int level = patches[static_cast<std::size_t>(k)].level;
    if (level != kNone) max_level = std::max(max_level, level);
  }
  for (int level = 0; level <= max_level; ++level) {
    for (int pass = 0; pass < settings.max_iterations; ++pass) {
      Progress progress;
      for (const int k : order) {
        Patch& p = patches[static_cast<std::size_t>(k)];
        if (p.level == level) ShockPatch(p, rows, vel, bodies, body_level, progress);
      }
      if (progress.Done(settings)) break;
    }
  }
}

int ShockFrozen(const Patch& p, const std::vector<int>& body_level) {
  const int la = body_level[static_cast<std::size_t>(p.a)];
  const int lb = p.b >= 0 ? body_level[static_cast<std::size_t>(p.b)] : -1;
  if (la == lb) return kShockSkipped;
  return la < lb ? p.a : p.b;
}

void ShockPatch(Patch& p, std::vector<Row>& rows, std::vector<Velocities>& vel, const BodyResponse& bodies,
                const std::vector<int>& body_level, Progress& progress) {
  const int frozen = ShockFrozen(p, body_level);
  if (frozen == kShockSkipped) return;
  for (int i = p.first; i < p.first + p.count; ++i) {
    Row& r = rows[static_cast<std::size_t>(i)];
    const Matrix3& K = frozen == r.a ? r.Kb : r.Ka;
    UpdateNormal(r, vel, frozen, 1.0 / r.n.dot(K * r.n), progress);
  }
  UpdateFriction(p, rows, vel, bodies, frozen, progress);
}

}  // namespace dynamics::contact
