// A small finite-element code for frames of straight Euler-Bernoulli beams
// (3-D frame elements, 6 DOFs per node), with lumped payloads and spring
// mounts, and the metrology frame of budgets/metrology_frame.yaml built with
// it. frame_model.cpp (deb-frame-model) writes that frame's modal tables;
// frame_fe_test.cpp checks the code against closed forms.
//
// DOFs: node n has DOFs 6n + c, c = 0..5: the translations u_x, u_y, u_z [m]
// and the small rotations theta_x, theta_y, theta_z [rad] about the global
// axes (right-handed, z up). A point rigidly attached to node n at the offset
// c (from the node) moves by u + theta x c: RigidOffset() gives that map.
//
// Element (length L, local axis x along it, local z the global z for a
// horizontal member; section properties below): axial EA, torsion GJ,
// bending EI_y (motion along local z, the vertical plane) and EI_z (motion
// along local y); cubic Hermite shape functions for bending, linear ones for
// the axial and torsion DOFs, and the consistent mass matrix (rho A for the
// translations, rho I_p for the torsion); no shear deformation and no rotary
// inertia of the section (Euler-Bernoulli: good while a bending half-wave is
// long against the section height).
#pragma once

#include <Eigen/Dense>
#include <string>
#include <vector>

namespace deb::frame {

inline constexpr double kTwoPi = 6.283185307179586476925286766559;

// A thin-walled rectangular tube: width along the local y axis (horizontal),
// height along the local z axis (vertical), both outer dimensions.
struct TubeSection {
  double e_pa = 0, g_pa = 0, density_kg_m3 = 0;
  double width_m = 0, height_m = 0, wall_m = 0;

  double AreaM2() const;
  double IVerticalM4() const;  // I_y: bending with motion along local z (vertical)
  double ILateralM4() const;   // I_z: bending with motion along local y (horizontal)
  double TorsionM4() const;    // J, Bredt's formula for a thin-walled closed section
  double MassPerLengthKgM() const { return density_kg_m3 * AreaM2(); }
};

// A straight member from one point to another, cut into `elements` equal
// elements; members that share an end point (or any node position) share
// the node: joints are rigid.
struct Member {
  Eigen::Vector3d from_m, to_m;
  int elements = 1;
};

// A rigid payload on the node at `node_m`, its centre of mass at `offset_m`
// from the node, with principal moments of inertia about its own centre of
// mass along the global axes.
struct PointMass {
  Eigen::Vector3d node_m, offset_m = Eigen::Vector3d::Zero();
  double mass_kg = 0;
  Eigen::Vector3d inertia_kg_m2 = Eigen::Vector3d::Zero();
};

// A mount (an isolator): three translational springs to the fixed floor
// along the global axes, acting on the point at `offset_m` from the node
// (e.g. the isolator's top plate below the frame's neutral axis).
struct Mount {
  Eigen::Vector3d node_m, offset_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d stiffness_n_m = Eigen::Vector3d::Zero();
};

struct FrameDescription {
  TubeSection section;
  std::vector<Member> members;
  std::vector<PointMass> masses;
  std::vector<Mount> mounts;
};

struct FeModel {
  std::vector<Eigen::Vector3d> nodes_m;
  Eigen::MatrixXd k, m;  // global stiffness [N/m, N, N m] and mass [kg, kg m, kg m^2]

  int dofs() const { return static_cast<int>(k.rows()); }
  // The node at `position_m` (within 1e-9 m). @throws std::runtime_error if there is none.
  int NodeAt(const Eigen::Vector3d& position_m) const;
};

// The 3 x 6 map from node DOFs to the translation of the point at `offset_m`
// from the node: [I, -[c]x].
Eigen::Matrix<double, 3, 6> RigidOffset(const Eigen::Vector3d& offset_m);

// @throws std::runtime_error for a zero-length member, an element count < 1,
//   a mass or mount on no node.
FeModel Assemble(const FrameDescription& frame);

// The rigid-body translation along `direction` (unit vector) as a DOF
// vector: the floor's influence vector r of a base motion in that direction.
Eigen::VectorXd RigidTranslation(int nodes, const Eigen::Vector3d& direction);

struct Modes {
  std::vector<double> f_hz;  // ascending
  Eigen::MatrixXd phi;       // dofs x modes, mass-normalised: phi^T M phi = I [1/sqrt(kg)]
};

// The modes of (K, M) at or below max_f_hz (K phi = w^2 M phi), each shape
// scaled to phi^T M phi = 1 and signed so that a fixed, irregularly weighted
// sum of its entries is positive (one sign whatever the eigensolver returns).
// Rigid-body modes (w^2 <= 0 numerically) get f = 0.
Modes SolveModes(const FeModel& model, double max_f_hz);

// A row over the DOFs giving the translation along `direction` of the point
// at `offset_m` from the node at `node_m`: shape value = row * phi.
Eigen::RowVectorXd PointRow(const FeModel& model, const Eigen::Vector3d& node_m, const Eigen::Vector3d& offset_m,
                            const Eigen::Vector3d& direction);

// A row giving the displacement along `direction` of the point at
// `offset_m` from the node at `point_node_m`, relative to the point at the
// same offset from the node at `reference_node_m`, in axes that move with
// the reference node (translate and rotate with it):
//   e = u_p - u_r - theta_r x (p - r).
// Any rigid-body motion of the whole structure gives e = 0.
Eigen::RowVectorXd RelativeRow(const FeModel& model, const Eigen::Vector3d& point_node_m,
                               const Eigen::Vector3d& reference_node_m, const Eigen::Vector3d& offset_m,
                               const Eigen::Vector3d& direction);

// ---------------------------------------------------------------------------
// The metrology frame of budgets/metrology_frame.yaml.

struct MetrologyFrameParameters {
  double length_m = 2.0, width_m = 1.0;  // along x and y
  int rails = 5;                         // along x, equally spaced in y (sides included)
  int cross_members = 9;                 // along y, equally spaced in x (ends included)
  double element_length_m = 0.0625;      // target; members are cut into equal elements
  // Aluminium (EN AW-6082) rectangular tube 80 x 120 x 6 mm.
  TubeSection section{70e9, 26.3e9, 2700, 0.080, 0.120, 0.006};
  // Payloads, their centres of mass below the frame's neutral axis.
  double head_mass_kg = 12, head_cog_depth_m = 0.15;  // optical sensor head at (1.5, 0)
  double reference_mass_kg = 8, reference_cog_depth_m = 0.10;  // reference block at (1.0, 0)
  double measurement_depth_m = 0.25;  // the head's and the reference's measurement points
  double stator_mass_kg = 20, stator_cog_depth_m = 0.08;  // stage stator at (0.5, -0.5)
  // Four isolators under the corners, their spring points below the neutral axis.
  double isolator_vertical_hz = 3.0, isolator_lateral_hz = 2.5, isolator_depth_m = 0.10;
  double zeta_isolation = 0.05, zeta_structure = 0.002;
  double isolation_band_hz = 20;  // modes below: isolation modes (zeta_isolation)
  double max_frequency_hz = 5000;
};

// Where things are on the frame (node positions, z = 0 plane).
struct MetrologyFrameLayout {
  Eigen::Vector3d head_m, reference_m, stage_m;
  std::vector<Eigen::Vector3d> isolators_m;
};

MetrologyFrameLayout MetrologyLayout(const MetrologyFrameParameters& p);
// Frame, payloads and isolators. The isolator stiffnesses give the whole
// mass, on four equal mounts, the vertical and lateral frequencies asked for:
// k_z = m_total (2 pi f_z)^2 / 4 per isolator, k_x = k_y likewise.
FrameDescription MetrologyFrame(const MetrologyFrameParameters& p);
double TotalMassKg(const FrameDescription& frame);

struct ModalTables {
  std::vector<double> f_hz, zeta;
  std::vector<std::string> stage_names, floor_names, output_names;
  Eigen::MatrixXd stage, floor, output;  // rows x modes
};

// The tables deb reads (see frame_model.cpp for what each holds).
ModalTables MetrologyTables(const MetrologyFrameParameters& p, const FeModel& model, const Modes& modes);

// One line per parameter, for the tables' header comment.
std::string DescribeParameters(const MetrologyFrameParameters& p, const FrameDescription& frame);

// Writes modes.csv, phi_in_stage.csv, phi_in_floor.csv and phi_out.csv into
// `dir` (which must exist), each headed by `comment` (lines prefixed "# ").
// Numbers as %.9g; a shape value below 1e-9 of its row's largest is written
// as 0 (round-off of a value that is zero by symmetry).
// @throws std::runtime_error if a file cannot be written.
void WriteTables(const ModalTables& tables, const std::string& dir, const std::string& comment);

}  // namespace deb::frame
