#pragma once
// The joined bodies of a World in reduced coordinates (internal).
//
// Every body of an articulated world is a node of a tree rooted in the world: the child of its
// joint, or of an implicit free joint when it has none. Spatial vectors are in world axes about
// the world origin (Featherstone 2008, ch. 2): a motion (ω, v_O), v_O the velocity of the body
// point at the origin; a force (n_O, f). The state is the joint positions q and the generalized
// momenta p = M(q) v; v is kept beside them. Each joint's motion subspace S is fixed in its child
// (a free joint's translation columns, along J_p's axes, in its parent, where V is the parent's),
// so Ṡ = V × S and the momentum equation is, joint by joint,
//     ṗ_i = Q_i + S_iᵀ (f_i − V_i ×* h_i)
// with h_i and f_i the spatial momentum and the external wrench of the subtree below joint i and
// Q_i the joint's own efforts (spring, damping, servo). The mass matrix is the composite-rigid-
// body algorithm's, factorized by Cholesky.

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "dynamics/constraints.h"
#include "dynamics/forces.h"
#include "dynamics/joints.h"
#include "dynamics/world.h"

namespace dynamics::contact {
struct Coupling;
}

namespace dynamics::internal {

using Vector6 = Eigen::Matrix<double, 6, 1>;
using Matrix6 = Eigen::Matrix<double, 6, 6>;
using MotionColumns = Eigen::Matrix<double, 6, Eigen::Dynamic, 0, 6, 6>;

/// The cross-product matrix [r]× (r × x = [r]× x).
inline Matrix3 CrossMatrix(const Vector3& r) {
  Matrix3 X;
  X << 0, -r.z(), r.y(), r.z(), 0, -r.x(), -r.y(), r.x(), 0;
  return X;
}

/// One body of the tree, parents before children.
struct Node {
  int body = 0;
  int parent = -1;  ///< node index, -1: the world
  int joint = -1;   ///< index in World::joints(), -1: an implicit free joint
  JointType type = JointType::kFree;
  Vector3 axis = Vector3::UnitZ();
  Matrix3 parent_rotation = Matrix3::Identity();  ///< J_p in the parent (or world)
  Vector3 parent_origin = Vector3::Zero();
  Matrix3 child_rotation = Matrix3::Identity();  ///< J_c in the child body
  Vector3 child_origin = Vector3::Zero();
  int q = 0, nq = 0;  ///< position slice
  int v = 0, nv = 0;  ///< velocity slice
  /// Where its quaternion starts in q (ball and free joints), -1: it has none.
  int quaternion() const { return type == JointType::kSpherical ? q : type == JointType::kFree ? q + 3 : -1; }
};

/// What the kinematics of one configuration gives each node.
struct NodeFrame {
  Matrix3 R;             ///< body axes → world
  Matrix3 rotational;    ///< the body's inertia about its centre of mass, world axes
  Vector3 x;             ///< center of mass, world
  Matrix3 joint_R;       ///< J_c → world
  Vector3 joint_origin;  ///< J_c's origin, world
  MotionColumns S;       ///< motion subspace, 6 × nv
  Matrix6 inertia;       ///< spatial inertia about the world origin
  Vector6 V;             ///< spatial velocity
};

/// The state a joint (or an unjoined body) starts from when it takes its body's: q and v of a
/// free joint from J_p (placed by the parent's frame R_p, x_p, V_p) to the child body b.
void FreeJointFromBody(const Node& node, const Matrix3& parent_R, const Vector3& parent_x, const Vector6& parent_V,
                       const RigidBody& b, double* q, double* v);
/// A joint's state read from the bodies (a world without articulation: lone free joints).
JointState JointStateFromBodies(const Joint& joint, const std::vector<RigidBody>& bodies);

/// World::AddJoint's checks of one joint against the bodies and the joints already there.
/// @throws std::invalid_argument naming the joint and the field.
void CheckJoint(const Joint& joint, int num_bodies, const std::vector<Joint>& existing);

/// One configuration's kinematics and mass matrix.
struct Configuration {
  std::vector<NodeFrame> frames;
  std::vector<Matrix6> composite;   ///< composite inertia of each subtree
  bool composites_current = false;  ///< composite was formed at q (not left by a kFrames Configure)
  /// M and its factor formed (else M⁻¹ is applied in O(n) by the articulated-body recursion;
  /// Densify forms them when a step needs them).
  bool dense = true;
  Eigen::MatrixXd M;  ///< the mass matrix's lower triangle (the upper is not kept), when dense
  Eigen::LLT<Eigen::MatrixXd> llt;
  Eigen::VectorXd diagonal;  ///< M's diagonal as Configure formed it (dense or not)
  Eigen::VectorXd q;         ///< the coordinates Configure placed it at
  /// Added to M's diagonal where it is factored or solved (not to the momenta p = M v): the midpoint
  /// solve's joint dampers and springs taken implicitly (Articulation::ImplicitDiagonal). Empty:
  /// none.
  Eigen::VectorXd implicit;
};

/// Bilateral rows at a configuration: values g (m) and Jacobian J (m × nv); each row's owner (a
/// loop's index, then the couplings' after the loops'; -1 a joint's pin, -2 − t tendon t's pin).
struct ConstraintRows {
  Eigen::MatrixXd J;
  Eigen::VectorXd g;
  std::vector<int> owner;
};

/// Coordinates held on a limit by a step's end: stops (a 1-dof joint's position and velocity
/// slots, and the limit) and tendon ends ((tendon, limit)).
struct Pins {
  struct Stop {
    int q, v;
    double limit;
  };
  std::vector<Stop> stops;
  std::vector<std::pair<int, double>> tendons;
};

/// Velocities held on rows J v = target through a mass matrix's factor: the least change in its
/// metric, x += M⁻¹Jᵀν with ν = (J M⁻¹ Jᵀ)⁺ (target − J x) (the pseudo-inverse: redundant rows
/// share nothing).
struct Projector {
  Eigen::MatrixXd J, Y, Ainv;  ///< the rows, M⁻¹Jᵀ, (J M⁻¹ Jᵀ)⁺
  void Form(const Eigen::LLT<Eigen::MatrixXd>& factor, const Eigen::MatrixXd& rows);
  bool active() const { return J.rows() > 0; }
  /// x moved onto J x = target; returns ν.
  Eigen::VectorXd Hold(Eigen::VectorXd& x, const Eigen::VectorXd& target) const;
  /// x moved onto J x = 0 (a response to an impulse, with the rows held).
  void Restrict(Eigen::VectorXd& x) const;
};

class Articulation {
 public:
  /// Builds the tree of `joints` over `bodies` (validated by World::AddJoint), takes the initial
  /// state (the joints' given positions and velocities; free joints and unjoined bodies keep
  /// their bodies' state) and places the bodies accordingly.
  /// @throws std::invalid_argument for a loop of joints.
  Articulation(const std::vector<Joint>& joints, std::vector<RigidBody>& bodies);

  /// Advances by h with the implicit midpoint rule on (q, p) or RK4; sub-steps when the midpoint
  /// solve does not converge. Writes the bodies' states.
  StepStatus Advance(Integrator integrator, const std::vector<std::unique_ptr<Force>>& forces, double t, double h,
                     std::vector<RigidBody>& bodies);
  // Contact steps (ContactWorld): symplectic Euler on (q, p) with impulses from outside, the
  // joints' springs, dampers and servos implicit (D, K their diagonal gains) —
  //   (M + h D + h² K) u = p + h ṗ(q, v) + h D v + Jᵀλ,  q ← q ⊕ h u,  p ← M(q) u.
  /// The kick p + h ṗ(q, v) at the start of the step (the state is kept): each body's (v, ω)
  /// after it into `kicked`. False: the mass matrix is not positive definite.
  bool ContactKick(const std::vector<std::unique_ptr<Force>>& forces, double t, double h, std::vector<Vector6>& kicked);
  /// Each body's tree, parent and whether it moves at all (after ContactKick).
  void Classify(contact::Coupling& coupling) const;
  /// How the `touched` bodies (those with contacts) answer impulses at the start of the step:
  /// each tree's touched members and their responses (after Classify).
  void Respond(contact::Coupling& coupling, const std::vector<char>& touched) const;
  /// Ends the step: each body's impulse (force and torque about its centre) and push-out
  /// (a pseudo-impulse that moves without changing velocities) added, then the joints' stops,
  /// friction and velocity motors; q moved by h; the bodies written.
  bool ContactFinish(const std::vector<Wrench>& impulses, const std::vector<Wrench>& pushes, double h,
                     std::vector<RigidBody>& bodies);
  JointState State(int joint) const;
  /// The world's loops, couplings and tendons (dynamics/constraints.h), before the first step.
  void SetConstraints(const std::vector<Loop>& loops, const std::vector<Coupling>& couplings,
                      const std::vector<Tendon>& tendons);
  /// Loops or couplings: rows the implicit midpoint rule holds (RK4 does not).
  bool Bilateral() const { return bilateral_; }
  ConstraintState LoopState(int k) const;
  ConstraintState CouplingState(int k) const;
  ConstraintState TendonState(int k) const;
  /// ½ k (L − rest)² over the tendons' springs, J.
  double TendonEnergy() const;
  /// Σ ½ k (q − rest)² over the joints' springs, J.
  double SpringEnergy() const;
  /// ½ Σ a q̇² of the joints' armatures (kinetic energy no body carries).
  double ArmatureEnergy() const;

 private:
  bool MidpointStep(const std::vector<std::unique_ptr<Force>>& forces, double t, double h,
                    std::vector<RigidBody>& bodies);
  /// The midpoint solve's first guess of v̄ and p1 (from the last steps' history).
  void Predict(double h);
  /// The midpoint rule's fixed-point iteration from the guess (false: it did not converge).
  bool IterateMidpoint(const std::vector<std::unique_ptr<Force>>& forces, double t, double h, Eigen::VectorXd& held);
  bool RK4Step(const std::vector<std::unique_ptr<Force>>& forces, double t, double h, std::vector<RigidBody>& bodies);
  /// Takes the step's end (q1_, p1_, configured in end_) as the state and writes the bodies.
  void Accept(std::vector<RigidBody>& bodies);
  /// A step of a tree without degrees of freedom.
  bool Still(std::vector<RigidBody>& bodies);
  /// What Configure forms: kinematics, composite inertias, the mass matrix and its factor (kDense);
  /// the kinematics, the composite inertias and M's diagonal (kSparse, O(n)); the kinematics alone
  /// (kFrames, O(n): the composites and the diagonal are left as they were, and Densify forms the
  /// composites again).
  enum class Form { kDense, kSparse, kFrames };
  /// The configuration at q in the given form (false: the mass matrix is not positive definite).
  bool Configure(const Eigen::VectorXd& q, Configuration& c, Form form = Form::kDense) const;
  /// kDense for trees that use the dense factor, else kSparse.
  Form StepForm() const { return Sparse() ? Form::kSparse : Form::kDense; }
  /// The composite inertia of each subtree, from c's frames.
  void Composites(Configuration& c) const;
  /// M and its factor for a configuration placed without them (false: not positive definite).
  bool Densify(Configuration& c) const;
  /// v = M⁻¹ p at configuration c: the factor when dense, else the articulated-body recursion
  /// (Featherstone's, with p in place of the joint forces and no velocity terms), O(n).
  void Solve(const Configuration& c, const Eigen::VectorXd& p, Eigen::VectorXd& v);
  /// Whether the implicit midpoint steps of this tree apply M⁻¹ by the O(n) recursion: more
  /// than kDenseLimit coordinates (a dense factorization is O(n³), several a step), and every
  /// joint of more than one coordinate at a root. (Below a ball joint, the articulated inertia
  /// loses its rotational block by cancellation, and D⁻¹ of a thin link's twist amplifies that
  /// level after level: 10⁻⁸ relative at 22 ball joints, the dense factor 10⁻¹⁶. Hinges and
  /// sliders keep to what M's conditioning allows.)
  bool Sparse() const { return recursion_ok_ && !bilateral_ && tendons_.empty() && v_.size() > kDenseLimit; }
  static constexpr Eigen::Index kDenseLimit = 64;
  /// Spatial velocities V of c's frames from v.
  void Velocities(const Eigen::VectorXd& v, Configuration& c) const;
  /// subtree_momentum_: Σ I V over each node's subtree, of configuration c (velocities set).
  void SubtreeMomenta(const Configuration& c);
  /// ṗ at (q, v) of configuration c (velocities set), time t.
  /// The joints' dampers and springs (and position servos' gains) as the midpoint solve takes them
  /// implicitly over a step of h: h/2 (c + kd) + h²/4 (k + kp) on each 1-dof joint's slot, h/2 c on
  /// a ball's. Added to M where the fixed-point iteration solves for v̄ (the right side gaining the
  /// same times the last iterate, so the fixed point is the midpoint rule's own), it keeps the
  /// iteration contracting for light links on damped joints (h c / I ≫ 1), as MuJoCo's implicit
  /// damping does. Empty when no joint has any.
  Eigen::VectorXd ImplicitDiagonal(double h) const;
  void MomentumRate(const std::vector<std::unique_ptr<Force>>& forces, double t, const Eigen::VectorXd& q,
                    const Eigen::VectorXd& v, const Configuration& c, std::vector<RigidBody>& stage,
                    Eigen::VectorXd& rate);
  /// q̇ at (q, v).
  void PositionRate(const Eigen::VectorXd& q, const Eigen::VectorXd& v, Eigen::VectorXd& rate) const;
  /// q ⊕ h v: positions moved by h v (a free joint's origin along J_p's axes), rotations by the
  /// exponential map of h ω (ω in J_c's axes).
  void Move(const Eigen::VectorXd& q, const Eigen::VectorXd& v, double h, Eigen::VectorXd& out) const;
  /// Stops, friction and velocity motors: impulses on p (with M at configuration c and the
  /// positions q1 reached without them). Returns the dofs held on a stop (and their limit).
  /// Returns whether any impulse was applied.
  bool Impulses(Configuration& c, const Eigen::VectorXd& q1, double h, Eigen::VectorXd& p1,
                std::vector<std::pair<int, double>>& stops);
  /// Writes the bodies' poses and motions from configuration c (its velocities set).
  /// `only` (optional): write just the bodies flagged there.
  void Sync(const Configuration& c, std::vector<RigidBody>& bodies, const std::vector<char>* only = nullptr) const;
  /// p = M(q) v, once before the first step (false: the mass matrix is not positive definite).
  bool EnsureMomenta();
  /// p = M v at configuration c (configured; its velocities set from v on the way).
  void Momenta(Configuration& c, const Eigen::VectorXd& v, Eigen::VectorXd& p);
  /// Places node i (its frame in c) from its parent's frame and q.
  void PlaceNode(int i, const Eigen::VectorXd& q, Configuration& c) const;
  /// Node `node`'s Jacobian in c: its body's (v, ω) = Φ u (6 × nv), into P (`path`: working).
  void BodyJacobian(const Configuration& c, int node, Eigen::MatrixXd& path, Eigen::MatrixXd& P) const;
  /// Σ Φᵀ w over the bodies' wrenches (force, torque about the centre), at the contact step's start.
  Eigen::VectorXd GeneralizedImpulse(const std::vector<Wrench>& w) const;

  // Loops, couplings and tendons (constraints.cpp).
  /// A point (and its frame's rotation) of a body in c, with its Jacobian: rows 0–2 the point's
  /// velocity, 3–5 the body's ω (world axes), 6 × nv.
  Vector3 PointOf(const Configuration& c, const BodyFrame& f, Matrix3* rotation, Eigen::MatrixXd* jacobian) const;
  /// A joint's position or a tendon's length at (c, q), with its gradient (nv).
  double CoordinateOf(const Configuration& c, const Eigen::VectorXd& q, const Coordinate& x,
                      Eigen::VectorXd* jacobian) const;
  double TendonLength(const Configuration& c, const Eigen::VectorXd& q, int t, Eigen::VectorXd* jacobian) const;
  /// A coupling's y − y₀ − P(x − x₀) at (c, q), with its gradient.
  double CouplingResidual(const Configuration& c, const Eigen::VectorXd& q, const Coupling& cp,
                          Eigen::VectorXd* jacobian) const;
  /// The loops' and couplings' rows, then the pins', at configuration c (its frames) and q.
  void BilateralRows(const Configuration& c, const Eigen::VectorXd& q, const Pins& pins, ConstraintRows& rows) const;
  /// q moved onto the rows (and pins) by Newton's method in the metric of `metric` (false: not
  /// finite); `moved`: whether q changed.
  bool ProjectPositions(const Eigen::LLT<Eigen::MatrixXd>& metric, const Pins& pins, const Configuration& at_q,
                        Eigen::VectorXd& q, bool& moved);
  /// p changed by the least impulse Jᵀν that makes v = M⁻¹p satisfy J v = 0 at c (dense).
  /// (Leaves the rows in rows_scratch_ and projector_ formed on them.)
  void HoldMomenta(const Configuration& c, const Eigen::VectorXd& q, Eigen::VectorXd& p, const Pins& pins = {});
  /// Rows the midpoint step holds: loops, couplings, taut tendons.
  bool Holds() const { return bilateral_ || !midpoint_pins_.tendons.empty(); }
  /// The tendons at an end of their range at q (configuration c; to 10⁻¹² of it), pinned there.
  void TautTendons(const Configuration& c, const Eigen::VectorXd& q, Pins& pins) const;
  /// Lets go of the taut tendons whose hold in the last midpoint solve pushed (a string cannot);
  /// true when any was let go.
  bool ReleasePushingPins();
  /// Adds scale ν of each row to its loop's or coupling's impulse of the step.
  void AddRowImpulses(const ConstraintRows& rows, const Eigen::VectorXd& nu, double scale);
  /// Σ J_Lᵀ f of the tendons' springs, dampers and motors into `rate`.
  void TendonEfforts(const Configuration& c, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                     Eigen::VectorXd& rate) const;
  /// The midpoint velocity v̄ held on the rows: J(q̄) v̄ = −g(q0)/h; the generalized impulse this
  /// adds over the step (2 Jᵀν) into `impulse`.
  void HoldMidpoint(const Configuration& mid, const Eigen::VectorXd& qbar, double h, Eigen::VectorXd& vbar,
                    Eigen::VectorXd& impulse);
  /// The tendons past an end of their range at (c, q): rows of stops for Impulses.
  /// Rows of stops (Impulses') for the tendons past an end of their range at q1 (v1 the end
  /// velocity), and their pins in tendon_pins_.
  void TendonStopRows(const Eigen::VectorXd& q1, const Eigen::VectorXd& v1);
  /// Loops, couplings or tendon ranges to hold at the end of a step.
  bool Constrained() const { return Holds() || !tendon_pins_.tendons.empty(); }
  /// After a step's impulses: q1_ onto the rows with the stops and tendon ends pinned, end_
  /// configured at it, p1_ onto the rows' tangent (false: not finite or not positive definite).
  bool FinishConstrained(const std::vector<std::pair<int, double>>& stops);
  void ClearConstraintImpulses(bool tendons = true);
  /// Classify's part: the trees that loops, couplings and tendons join made one.
  void MergeConstrainedTrees(std::vector<int>& tree) const;

  std::vector<Loop> loops_;
  std::vector<Coupling> couplings_;
  std::vector<Tendon> tendons_;
  bool bilateral_ = false;
  std::vector<double> coupling_impulse_, tendon_impulse_;  ///< last step
  std::vector<Vector6> loop_impulse_;                      ///< last step, each of a loop's rows (at most six)
  Eigen::VectorXd start_gap_;                              ///< g(q0) of the step being solved
  mutable Configuration probe_;
  ConstraintRows rows_scratch_;
  Projector projector_;
  /// The rows the step's impulses see held (J v = held_target_), formed by the step: empty when
  /// there are none.
  Projector held_rows_;
  Eigen::VectorXd held_target_, held_nu_;
  ConstraintRows held_source_;                  ///< the contact step's rows at its start (held_rows_' J and owners)
  Pins tendon_pins_;                            ///< the tendons Impulses stopped at an end of their range
  Pins midpoint_pins_;                          ///< the taut tendons the midpoint step holds
  std::vector<Eigen::VectorXd> row_jacobians_;  ///< Impulses' rows on tendons (empty: a joint's dof)

  std::vector<Joint> joints_;
  std::vector<Node> nodes_;
  std::vector<int> node_of_joint_, node_of_body_;
  std::vector<RigidBody> inertias_;  ///< mass and principal moments of each body (the rest unused)
  Eigen::VectorXd q_, v_, p_;
  std::vector<double> limit_impulse_, drive_impulse_;  ///< per joint, last step
  // Scratch.
  Configuration start_, mid_, end_;
  std::vector<RigidBody> stage_;
  std::vector<Wrench> wrenches_;
  std::vector<Vector6> subtree_momentum_, subtree_force_;
  /// The last midpoint steps' ṗ and midpoint velocities, newest first, and their lengths: the
  /// predictor of the next step's solve.
  struct MidpointHistory {
    static constexpr int kKept = 3;
    Eigen::VectorXd rate[kKept], vbar[kKept];
    double h[kKept] = {0, 0, 0};
    int count = 0;
    void Push(const Eigen::VectorXd& r, const Eigen::VectorXd& v, double step) {
      for (int k = kKept - 1; k > 0; --k) rate[k].swap(rate[k - 1]), vbar[k].swap(vbar[k - 1]), h[k] = h[k - 1];
      rate[0] = r, vbar[0] = v, h[0] = step;  // (into kept capacity)
      count = std::min(count + 1, kKept);
    }
    void Clear() { count = 0; }
  };
  MidpointHistory history_;
  Eigen::VectorXd saved_q_, saved_v_, saved_p_;  ///< the state before a step that may be retried
  Eigen::VectorXd q0_, p0_, q1_, p1_, vbar_, vnew_, pnew_, rate_, k_[4], kq_[4], qs_, ps_, vs_, v_end_;
  struct Row {
    int joint, dof;
    double lo, hi, target;
    bool stop;
    int drive = -1;   ///< a drive row's slot in drive_mode_ (the motor's 2 dof, the friction's 2 dof + 1)
    int tendon = -1;  ///< a tendon's stop (its Jacobian in row_jacobians_; joint and dof -1)
  };
  std::vector<Row> rows_;
  bool momenta_ready_ = false;
  bool start_formed_ = false;  // start_ was configured densely (its factor computed) at least once
  bool recursion_ok_ = false;  ///< no joint of several coordinates below a root (Sparse)
  Eigen::VectorXd kicked_p_;   ///< ContactKick's p + h ṗ (+ h D v)
  Configuration effective_;    ///< ContactKick's M + h D + h² K and its factor (nothing else)
  /// Dofs ContactKick holds on a stop (-1 the lower, +1 the upper; Impulses leaves their stops),
  /// and those the last contact step left pressed on one (held again in the next).
  std::vector<signed char> held_, stuck_;
  /// The velocity motor's and the friction's rows of a 1-dof joint in a contact step
  /// (DriveInKick), two per coordinate (2 dof: the motor's, 2 dof + 1: the friction's): what each
  /// did in the last step — held at its target rate in a contact step (kDriveHeld) or in a step
  /// without contact (kDriveFree), or ±1, pushed at its bound in that direction; which coordinates
  /// ContactKick drives (Impulses leaves their rows), and the damper gain h D of each row it holds
  /// (0: pushed at the bound, or held by the motor's damper).
  static constexpr signed char kDriveHeld = 0, kDriveFree = 2;
  std::vector<signed char> drive_mode_;
  std::vector<char> driven_;
  std::vector<double> drive_gain_;
  /// A joint's two rows for a step of length h: whether each acts, its bound (N·m·s or N·s) and
  /// its target rate ([0] the velocity motor, [1] the friction).
  struct DriveRows {
    bool on[2] = {false, false};
    double bound[2] = {0, 0}, target[2] = {0, 0};
  };
  static DriveRows DriveRowsOf(const Joint& j, double h);
  /// ContactKick's part: joint n's friction and velocity motor in the contact step's own solve.
  void DriveInKick(const Node& n, const Joint& j, double h);
  /// ContactFinish's part: each driven row's impulse from the step's velocities `u`, and its
  /// mode for the next step.
  void DriveAfterContacts(const Eigen::VectorXd& u, double h);
  /// Respond's working arrays (a step like the one before allocates nothing): the touched bodies'
  /// Jacobians Φ, M⁻¹ Φᵀ, and a Jacobian's path columns.
  mutable std::vector<Eigen::MatrixXd> phi_, solved_;
  mutable Eigen::MatrixXd path_;
  /// Solve's recursion, per node, about its joint's origin: articulated inertia, bias, S, U = I^A S,
  /// D⁻¹, u, and the spatial velocity of its frame.
  using SmallMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 6, 6>;
  using SmallVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 6, 1>;
  std::vector<Matrix6> aba_inertia_;
  std::vector<Vector6> aba_bias_, aba_velocity_;
  std::vector<MotionColumns> aba_s_, aba_u_;
  std::vector<SmallMatrix> aba_d_inverse_;
  std::vector<SmallVector> aba_rhs_;
};

}  // namespace dynamics::internal
