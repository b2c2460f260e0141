// An island's contacts solved as a block (solver_internal.h). A tree answers an impulse at one
// foot with every member's motion (Coupling::Apply: a 6 × 6 product per member), and its
// contacts couple through the legs, so the point-by-point sweeps both cost much and converge
// slowly (a quadruped at rest ran out of its 32 sweeps every step). Free bodies leaning on each
// other crawl the same way (a column of tilted boxes: each sweep cut the change by ~4 %). Here the
// island's channels — each row's normal and each patch's friction directions (t1, t2, ρ n) — get
// their Delassus matrix A = J M⁻¹ Jᵀ once a step (U = M⁻¹ Jᵀ from the coupling's blocks, or a
// free body's own 1/m and I⁻¹; A = J U), and the sweeps work on the channels' velocities u = J v
// alone (solver.cpp comes here once the sweeps of kernels.cpp slow down):
// - a pivoting step first: the loaded rows and the friction of every loaded patch solved as one
//   linear system (regularized Cholesky of their block of A over its rows' profiles — banded for
//   a column of free bodies, whose channels come from the ground up — then iterative refinement),
//   principal pivoting on the normals, accepted only when it is the answer of the
//   complementarity problem — loaded points push, the others separate, every patch's friction
//   within μ N — which the sweeps converge to;
// - else (SolveBlock, jointed bodies) a projected Gauss–Seidel sweep on A, with the updates of
//   kernels.cpp (the least normal impulse that keeps a point at its target; friction that stops
//   the patch when it can, else the impulse of least kinetic energy on the limit μ N); a sweep
//   costs O(m²) for m channels, and stops on the same m/s rule as the others. A patch that must
//   slide is left to the projected sweeps (the pivoting step holds friction only);
// - else (PivotFree, free bodies) nothing: their own sweeps cost less than a projected one, and
//   solver.cpp goes on with them. A free body's channels meet only the channels of the patches
//   that share its body, so their A is built entry by entry (FreeDelassus).

#include <algorithm>
#include <cmath>
#include <limits>

#include "solver_internal.h"

namespace dynamics::contact {
namespace {

using Vector6 = Eigen::Matrix<double, 6, 1>;

// Where body `body` is among the island's members (sorted), or -1.
int LocalIndex(const std::vector<int>& members, int body) {
  const auto at = std::lower_bound(members.begin(), members.end(), body);
  return at != members.end() && *at == body ? static_cast<int>(at - members.begin()) : -1;
}

// The island's channels: for each patch in order, its rows' normals, then its friction's nf
// directions (2, or 3 with a torsion radius). Each channel's unit impulse is the wrench wa on a
// and −wb on b (force, torque about the body's centre); its velocity is wa·V_a − wb·V_b.
void BuildChannels(const std::vector<Row>& rows, const std::vector<Patch>& patches, const std::vector<int>& order,
                   BlockScratch& s) {
  s.Reserve();
  s.channels.clear();
  s.first.clear();
  for (const int k : order) {
    const Patch& p = patches[static_cast<std::size_t>(k)];
    s.first.push_back(static_cast<int>(s.channels.size()));
    for (int i = p.first; i < p.first + p.count; ++i) {
      const Row& r = rows[static_cast<std::size_t>(i)];
      BlockChannel c;
      c.a = r.a;
      c.b = r.b;
      c.wa << r.n, r.ang_a;
      c.wb << r.n, r.ang_b;
      c.target = r.target;
      c.normal = true;
      s.channels.push_back(c);
    }
    const int nf = p.rho > 0 ? 3 : 2;
    for (int f = 0; f < nf; ++f) {
      BlockChannel c;
      c.a = p.a;
      c.b = p.b;
      const Vector3 t = f == 0 ? p.t1 : f == 1 ? p.t2 : Vector3::Zero().eval();
      c.wa << t, p.ang_a.col(f);
      c.wb << t, p.ang_b.col(f);
      s.channels.push_back(c);
    }
  }
}

// The island's members: every touched body of the trees its patches touch (sorted); of free
// bodies (no coupling), the patches' bodies.
void BuildMembers(const std::vector<Patch>& patches, const std::vector<int>& order, const Coupling* coupling,
                  BlockScratch& s) {
  s.members.clear();
  for (const int k : order) {
    const Patch& p = patches[static_cast<std::size_t>(k)];
    for (const int body : {p.a, p.b}) {
      if (body < 0) continue;
      if (coupling == nullptr) {
        s.members.push_back(body);
        continue;
      }
      const auto& tree = coupling->members[static_cast<std::size_t>(coupling->tree[static_cast<std::size_t>(body)])];
      s.members.insert(s.members.end(), tree.begin(), tree.end());
    }
  }
  std::sort(s.members.begin(), s.members.end());
  s.members.erase(std::unique(s.members.begin(), s.members.end()), s.members.end());
}

// The channels' velocities u = J V of the velocities `vel`.
void ChannelVelocities(const std::vector<Velocities>& vel, BlockScratch& s) {
  const auto m = static_cast<Eigen::Index>(s.channels.size());
  s.u.resize(m);
  for (Eigen::Index c = 0; c < m; ++c) {
    const BlockChannel& ch = s.channels[static_cast<std::size_t>(c)];
    const Velocities& va = vel[static_cast<std::size_t>(ch.a)];
    s.u[c] = ch.wa.head<3>().dot(va.v) + ch.wa.tail<3>().dot(va.w);
    if (ch.b >= 0) {
      const Velocities& vb = vel[static_cast<std::size_t>(ch.b)];
      s.u[c] -= ch.wb.head<3>().dot(vb.v) + ch.wb.tail<3>().dot(vb.w);
    }
  }
}

// A = J U of free bodies, entry by entry where two channels share a body (elsewhere zero): a
// column of boxes touches each channel's row with a dozen others, not the island's every one.
void FreeDelassus(BlockScratch& s) {
  const auto m = static_cast<Eigen::Index>(s.channels.size());
  const std::size_t n = s.members.size();
  // Each channel's bodies (their places among the members), and each member's channels.
  s.sides.resize(2 * static_cast<std::size_t>(m));
  s.touch_first.assign(n + 1, 0);
  for (Eigen::Index c = 0; c < m; ++c) {
    const BlockChannel& ch = s.channels[static_cast<std::size_t>(c)];
    const int la = LocalIndex(s.members, ch.a), lb = ch.b >= 0 ? LocalIndex(s.members, ch.b) : -1;
    s.sides[static_cast<std::size_t>(2 * c)] = la;
    s.sides[static_cast<std::size_t>(2 * c + 1)] = lb;
    ++s.touch_first[static_cast<std::size_t>(la) + 1];
    if (lb >= 0) ++s.touch_first[static_cast<std::size_t>(lb) + 1];
  }
  for (std::size_t j = 0; j < n; ++j) s.touch_first[j + 1] += s.touch_first[j];
  s.touch.resize(static_cast<std::size_t>(s.touch_first[n]));
  s.touch_fill.assign(s.touch_first.begin(), s.touch_first.end() - 1);
  for (Eigen::Index c = 0; c < m; ++c) {
    for (int side = 0; side < 2; ++side) {
      const int l = s.sides[static_cast<std::size_t>(2 * c + side)];
      if (l >= 0) s.touch[static_cast<std::size_t>(s.touch_fill[static_cast<std::size_t>(l)]++)] = static_cast<int>(c);
    }
  }
  s.A.setZero(m, m);
  for (Eigen::Index c = 0; c < m; ++c) {
    const BlockChannel& ch = s.channels[static_cast<std::size_t>(c)];
    for (int side = 0; side < 2; ++side) {
      const int l = s.sides[static_cast<std::size_t>(2 * c + side)];
      if (l < 0) continue;
      const Vector6& w = side == 0 ? ch.wa : ch.wb;
      const double sign = side == 0 ? 1.0 : -1.0;
      for (int k = s.touch_first[static_cast<std::size_t>(l)]; k < s.touch_first[static_cast<std::size_t>(l) + 1];
           ++k) {
        const int d = s.touch[static_cast<std::size_t>(k)];
        s.A(c, d) += sign * w.dot(s.U.col(d).segment<6>(6 * l));
      }
    }
  }
}

// U (each channel's unit impulse's change of every member's (v, ω), 6 rows a member), the
// Delassus matrix A = J U, and the channels' velocities J V of the velocities `vel`. A free body
// (no coupling) answers a wrench alone: (f / m, I⁻¹ τ).
void BuildResponse(const std::vector<Velocities>& vel, const BodyResponse& bodies, const Coupling* coupling,
                   BlockScratch& s) {
  const auto m = static_cast<Eigen::Index>(s.channels.size());
  const auto n = static_cast<Eigen::Index>(s.members.size());
  s.U.setZero(6 * n, m);
  for (Eigen::Index d = 0; d < m; ++d) {
    const BlockChannel& c = s.channels[static_cast<std::size_t>(d)];
    auto add = [&](int body, const Vector6& w, double sign) {
      if (coupling == nullptr) {
        const auto k = static_cast<std::size_t>(body);
        auto column = s.U.col(d).segment<6>(6 * LocalIndex(s.members, body));
        column.head<3>() += (sign * bodies.inv_mass[k]) * w.head<3>();
        column.tail<3>().noalias() += sign * (bodies.inv_inertia[k] * w.tail<3>());
        return;
      }
      const auto t = static_cast<std::size_t>(coupling->tree[static_cast<std::size_t>(body)]);
      for (const int j : coupling->members[t]) {
        s.U.col(d).segment<6>(6 * LocalIndex(s.members, j)).noalias() += sign * (coupling->Response(j, body) * w);
      }
    };
    add(c.a, c.wa, 1.0);
    if (c.b >= 0) add(c.b, c.wb, -1.0);
  }
  if (coupling == nullptr) {
    FreeDelassus(s);
  } else {
    s.A.resize(m, m);
    for (Eigen::Index c = 0; c < m; ++c) {
      const BlockChannel& ch = s.channels[static_cast<std::size_t>(c)];
      const Eigen::Index ia = 6 * LocalIndex(s.members, ch.a);
      s.A.row(c).noalias() = ch.wa.transpose() * s.U.middleRows<6>(ia);
      if (ch.b >= 0) {
        const Eigen::Index ib = 6 * LocalIndex(s.members, ch.b);
        s.A.row(c).noalias() -= ch.wb.transpose() * s.U.middleRows<6>(ib);
      }
    }
  }
  ChannelVelocities(vel, s);
}

// The impulses of the channels from the rows and patches (the warm start), and back.
void GatherImpulses(const std::vector<Row>& rows, const std::vector<Patch>& patches, const std::vector<int>& order,
                    BlockScratch& s) {
  s.lambda.resize(static_cast<Eigen::Index>(s.channels.size()));
  for (std::size_t q = 0; q < order.size(); ++q) {
    const Patch& p = patches[static_cast<std::size_t>(order[q])];
    Eigen::Index c = s.first[q];
    for (int i = p.first; i < p.first + p.count; ++i) s.lambda[c++] = rows[static_cast<std::size_t>(i)].lambda_n;
    for (int f = 0; f < (p.rho > 0 ? 3 : 2); ++f) s.lambda[c++] = p.lambda[f];
  }
}
void ScatterImpulses(const BlockScratch& s, const std::vector<int>& order, std::vector<Row>& rows,
                     std::vector<Patch>& patches) {
  for (std::size_t q = 0; q < order.size(); ++q) {
    Patch& p = patches[static_cast<std::size_t>(order[q])];
    Eigen::Index c = s.first[q];
    for (int i = p.first; i < p.first + p.count; ++i) rows[static_cast<std::size_t>(i)].lambda_n = s.lambda[c++];
    p.lambda.setZero();
    for (int f = 0; f < (p.rho > 0 ? 3 : 2); ++f) p.lambda[f] = s.lambda[c++];
  }
}

// A change d of channel c's impulse: every channel's velocity follows.
void Change(BlockScratch& s, Eigen::Index c, double d) {
  if (d == 0) return;
  s.lambda[c] += d;
  s.u.noalias() += s.A.col(c) * d;
}

// One projected Gauss–Seidel sweep over the patches (forward or backward): each row's normal,
// then the patch's friction.
void ProjectedSweep(std::vector<Patch>& patches, const std::vector<int>& order, bool forward, BlockScratch& s,
                    Progress& progress) {
  const auto n = static_cast<std::ptrdiff_t>(order.size());
  for (std::ptrdiff_t k = 0; k < n; ++k) {
    const std::size_t q = static_cast<std::size_t>(forward ? k : n - 1 - k);
    Patch& p = patches[static_cast<std::size_t>(order[q])];
    const Eigen::Index first = s.first[q], nf = p.rho > 0 ? 3 : 2;
    double N = 0;
    for (Eigen::Index c = first; c < first + p.count; ++c) {
      if (!(s.A(c, c) > 0)) {  // no motion of the trees moves the point along its normal
        N += s.lambda[c];
        continue;
      }
      const double mass = 1 / s.A(c, c);
      const double ln = std::max(s.lambda[c] + mass * (s.channels[static_cast<std::size_t>(c)].target - s.u[c]), 0.0);
      const double d = ln - s.lambda[c];
      Change(s, c, d);
      N += ln;
      progress.change = std::max(progress.change, std::abs(d));
      progress.scale = std::max(progress.scale, ln);
      progress.speed = std::max(progress.speed, std::abs(d) / mass);
    }
    const Eigen::Index f0 = first + p.count;
    Vector3 g = Vector3::Zero(), old = Vector3::Zero();
    for (Eigen::Index f = 0; f < nf; ++f) {
      g[f] = s.u[f0 + f];
      old[f] = s.lambda[f0 + f];
    }
    const Vector3 lt = FrictionUpdate(p, old, g, p.mass, p.Ka, p.mu * N);
    const Vector3 d = lt - old;
    for (Eigen::Index f = 0; f < nf; ++f) Change(s, f0 + f, d[f]);
    progress.change = std::max(progress.change, d.norm());
    progress.scale = std::max(progress.scale, lt.norm());
    progress.speed = std::max(progress.speed, (p.Ka * d).norm());
  }
}

// Roles of the channels in the pivoting step.
enum Role : char {
  kUnloaded = 0,  // a row without load: its impulse set to zero
  kSolved = 1,    // a loaded row, or the friction of a loaded patch: its velocity at its target
  kZeroed = 2,    // the friction of a patch without load: zero
};

// The linear system of one set of roles: s.delta, the change of every channel's impulse, and
// s.change_u, of its velocity. The set's block of A is factored (Cholesky over its rows'
// profiles: the channels come patch by patch from the ground up, so free bodies' islands give
// banded blocks; kept while the set holds) with kBlockRegularization of its diagonal added: a
// tree has fewer degrees of freedom than its contacts have channels, and legs held on their stops
// make the rest ill-conditioned. The regularized solve changes the impulses least where they are
// not determined (the warm start's sharing of a load is kept), and iterative refinement solves
// the determined part to a tenth of the tolerance (m/s). False where that fails.
bool SolveSet(double tolerance, BlockScratch& s) {
  constexpr int kRefinements = 40;
  const auto m = static_cast<Eigen::Index>(s.channels.size());
  s.index.clear();
  for (Eigen::Index c = 0; c < m; ++c) {
    if (s.role[static_cast<std::size_t>(c)] == kSolved) s.index.push_back(static_cast<int>(c));
  }
  const auto k = static_cast<Eigen::Index>(s.index.size());
  if (k == 0) return false;
  // −λ where the impulse goes; on the set, S d = target − u − A (the others' change).
  s.delta.setZero(m);
  for (Eigen::Index c = 0; c < m; ++c) {
    if (s.role[static_cast<std::size_t>(c)] != kSolved) s.delta[c] = -s.lambda[c];
  }
  s.rhs.resize(k);
  for (Eigen::Index i = 0; i < k; ++i) {
    const Eigen::Index c = s.index[static_cast<std::size_t>(i)];
    s.rhs[i] = s.channels[static_cast<std::size_t>(c)].target - s.u[c] - s.A.row(c).dot(s.delta);
  }
  if (s.index != s.factored) {
    s.factored = s.index;
    s.S0.resize(k, k);
    for (Eigen::Index i = 0; i < k; ++i) {
      const auto ci = s.index[static_cast<std::size_t>(i)];
      for (Eigen::Index j = 0; j < k; ++j) s.S0(i, j) = s.A(ci, s.index[static_cast<std::size_t>(j)]);
    }
    s.factor_ok = s.cholesky.Compute(s.S0, kBlockRegularization);
  }
  if (!s.factor_ok) return false;
  s.solved = s.rhs;
  s.cholesky.SolveInPlace(s.solved);
  double before = std::numeric_limits<double>::infinity();
  for (int refinement = 0;; ++refinement) {
    s.residual.noalias() = s.rhs - s.S0 * s.solved;
    const double residual = s.residual.cwiseAbs().maxCoeff();
    if (!std::isfinite(residual)) return false;
    if (residual <= 0.1 * tolerance) break;
    // Refinement halves a determined residual at least every step (or the set's equations
    // contradict each other: more channels than degrees of freedom, targets no motion meets).
    if (refinement == kRefinements || residual > 0.5 * before) return false;
    before = residual;
    s.cholesky.SolveInPlace(s.residual);
    s.solved += s.residual;
  }
  for (Eigen::Index i = 0; i < k; ++i) s.delta[s.index[static_cast<std::size_t>(i)]] = s.solved[i];
  s.change_u.noalias() = s.A * s.delta;
  return true;
}

// The worst point of a solved set: a loaded one pulling (the most negative load), else an
// unloaded one sinking (the most negative velocity beyond its target, below −tolerance); -1: none.
Eigen::Index WorstPoint(const BlockScratch& s, double tolerance) {
  const auto m = static_cast<Eigen::Index>(s.channels.size());
  Eigen::Index worst = -1;
  double pull = 0, sink = -tolerance;
  for (Eigen::Index c = 0; c < m; ++c) {
    if (!s.channels[static_cast<std::size_t>(c)].normal || s.role[static_cast<std::size_t>(c)] != kSolved) continue;
    const double ln = s.lambda[c] + s.delta[c];
    if (ln < pull) {
      pull = ln;
      worst = c;
    }
  }
  if (worst >= 0) return worst;
  for (Eigen::Index c = 0; c < m; ++c) {
    if (!s.channels[static_cast<std::size_t>(c)].normal || s.role[static_cast<std::size_t>(c)] == kSolved) continue;
    const double w = s.u[c] + s.change_u[c] - s.channels[static_cast<std::size_t>(c)].target;
    if (w < sink) {
      sink = w;
      worst = c;
    }
  }
  return worst;
}

// Each patch's friction role: solved where one of its points is loaded, else zero.
void SetFrictionRoles(const std::vector<Patch>& patches, const std::vector<int>& order, BlockScratch& s) {
  for (std::size_t q = 0; q < order.size(); ++q) {
    const Patch& p = patches[static_cast<std::size_t>(order[q])];
    const Eigen::Index first = s.first[q], f0 = first + p.count, nf = p.rho > 0 ? 3 : 2;
    bool loaded = false;
    for (Eigen::Index c = first; c < f0; ++c) loaded |= s.role[static_cast<std::size_t>(c)] == kSolved;
    for (Eigen::Index f = 0; f < nf; ++f)
      s.role[static_cast<std::size_t>(f0 + f)] = loaded && p.mu > 0 ? kSolved : kZeroed;
  }
}

// Whether every loaded patch's friction of the solved set lies within μ N.
bool WithinFriction(const std::vector<Patch>& patches, const std::vector<int>& order, const BlockScratch& s) {
  for (std::size_t q = 0; q < order.size(); ++q) {
    const Patch& p = patches[static_cast<std::size_t>(order[q])];
    const Eigen::Index first = s.first[q], f0 = first + p.count, nf = p.rho > 0 ? 3 : 2;
    double N = 0;
    for (Eigen::Index c = first; c < f0; ++c) N += s.lambda[c] + s.delta[c];
    Vector3 lt = Vector3::Zero();
    for (Eigen::Index f = 0; f < nf; ++f) lt[f] = s.lambda[f0 + f] + s.delta[f0 + f];
    if (!(lt.norm() <= p.mu * N)) return false;
  }
  return true;
}

// The pivoting step: the loaded rows and every loaded patch's friction solved together (each
// loaded point's normal velocity at its target, each loaded patch's sliding and turning stopped,
// an unloaded patch's friction zero). From the points loaded now, a point whose load would turn
// negative is let go, or one that would sink is loaded — the worst one at a time, a few times
// (principal pivoting) — until the set is the normals' answer: the loaded points push, the others
// separate. Accepted only when every patch's friction then lies within μ N: that is the answer
// of the contacts' complementarity problem, the sweeps' fixed point. False, with nothing
// changed, otherwise (a patch that slides): the sweeps go on.
bool PivotStep(const std::vector<Patch>& patches, const std::vector<int>& order, double tolerance, BlockScratch& s,
               Progress& progress) {
  const auto m = static_cast<Eigen::Index>(s.channels.size());
  s.role.assign(static_cast<std::size_t>(m), kUnloaded);
  for (Eigen::Index c = 0; c < m; ++c) {
    if (s.lambda[c] > 0 && s.channels[static_cast<std::size_t>(c)].normal)
      s.role[static_cast<std::size_t>(c)] = kSolved;
  }
  // A set that failed is not tried again until the sweeps change it.
  if (s.role == s.failed) return false;
  s.failed = s.role;
  SetFrictionRoles(patches, order, s);
  constexpr int kPivots = 8;
  for (int pivot = 0;; ++pivot) {
    if (pivot == kPivots || !SolveSet(tolerance, s)) return false;
    const Eigen::Index worst = WorstPoint(s, 1e-9 * s.rhs.cwiseAbs().maxCoeff());
    if (worst < 0) break;
    auto& role = s.role[static_cast<std::size_t>(worst)];
    role = role == kSolved ? kUnloaded : kSolved;
    SetFrictionRoles(patches, order, s);
  }
  if (!WithinFriction(patches, order, s)) return false;
  s.failed.clear();
  s.lambda += s.delta;
  s.u += s.change_u;
  for (Eigen::Index c = 0; c < m; ++c) {
    progress.change = std::max(progress.change, std::abs(s.delta[c]));
    progress.scale = std::max(progress.scale, std::abs(s.lambda[c]));
    progress.speed = std::max(progress.speed, std::abs(s.change_u[c]));
  }
  return true;
}

// The block's impulses into the rows and patches, and their change into the members' velocities
// (all at once).
void Finish(const std::vector<int>& order, std::vector<Row>& rows, std::vector<Patch>& patches,
            std::vector<Velocities>& vel, BlockScratch& s) {
  ScatterImpulses(s, order, rows, patches);
  s.change_v.noalias() = s.U * (s.lambda - s.start);
  for (std::size_t j = 0; j < s.members.size(); ++j) {
    Velocities& v = vel[static_cast<std::size_t>(s.members[j])];
    v.v += s.change_v.segment<3>(static_cast<Eigen::Index>(6 * j));
    v.w += s.change_v.segment<3>(static_cast<Eigen::Index>(6 * j + 3));
  }
}

}  // namespace

BlockKind BlockKindOf(const std::vector<Patch>& patches, const std::vector<int>& order, const BodyResponse& bodies) {
  if (order.empty()) return BlockKind::kNone;
  const bool jointed = patches[static_cast<std::size_t>(order[0])].coupling != nullptr;
  if (!jointed && order.size() == 1) return BlockKind::kNone;  // (a free patch alone: UpdatePatchJointly)
  int channels = 0;
  for (const int k : order) {
    const Patch& p = patches[static_cast<std::size_t>(k)];
    // A patch that slid last step follows its centre of pressure within the sweeps (its
    // friction's channels move with it): kernels.cpp's sweeps. An island of jointed and free
    // bodies both: the sweeps too.
    if (p.sliding || (p.coupling != nullptr) != jointed) return BlockKind::kNone;
    channels += p.count + (p.rho > 0 ? 3 : 2);
  }
  if ((jointed && bodies.coupling == nullptr) || channels > kMaxBlockChannels) return BlockKind::kNone;
  return jointed ? BlockKind::kJointed : BlockKind::kFree;
}

int SolveBlock(std::vector<Row>& rows, std::vector<Patch>& patches, const std::vector<int>& order,
               std::vector<Velocities>& vel, const BodyResponse& bodies, const SolveSettings& settings,
               BlockScratch& s) {
  BuildChannels(rows, patches, order, s);
  BuildMembers(patches, order, bodies.coupling, s);
  BuildResponse(vel, bodies, bodies.coupling, s);
  GatherImpulses(rows, patches, order, s);
  s.start = s.lambda;
  s.factored.clear();
  s.failed.clear();
  int sweeps = settings.max_iterations;
  for (int iteration = 0; iteration < settings.max_iterations; ++iteration) {
    // An accepted pivoting step is the answer (the conditions it checks are the sweeps' fixed
    // point): no sweep after it would move a contact by more than rounding.
    Progress progress;
    if (PivotStep(patches, order, settings.speed_tolerance, s, progress)) {
      sweeps = iteration + 1;
      break;
    }
    ProjectedSweep(patches, order, iteration % 2 == 0, s, progress);
    if (progress.Done(settings)) {
      sweeps = iteration + 1;
      break;
    }
  }
  Finish(order, rows, patches, vel, s);
  return sweeps;
}

bool PivotFree(std::vector<Row>& rows, std::vector<Patch>& patches, const std::vector<int>& order,
               std::vector<Velocities>& vel, const BodyResponse& bodies, const SolveSettings& settings, BlockScratch& s,
               bool first) {
  if (first) {
    BuildChannels(rows, patches, order, s);
    BuildMembers(patches, order, nullptr, s);
    BuildResponse(vel, bodies, nullptr, s);
    s.factored.clear();
    s.failed.clear();
  } else {
    ChannelVelocities(vel, s);
  }
  GatherImpulses(rows, patches, order, s);
  s.start = s.lambda;
  Progress progress;
  if (!PivotStep(patches, order, settings.speed_tolerance, s, progress)) return false;
  Finish(order, rows, patches, vel, s);
  return true;
}

}  // namespace dynamics::contact
