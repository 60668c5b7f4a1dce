#include "examples/metrology_frame/frame_fe.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace deb::frame {

namespace {

using Matrix12 = Eigen::Matrix<double, 12, 12>;
using Matrix6 = Eigen::Matrix<double, 6, 6>;

Eigen::Matrix3d Skew(const Eigen::Vector3d& c) {
  Eigen::Matrix3d s;
  s << 0, -c.z(), c.y(), c.z(), 0, -c.x(), -c.y(), c.x(), 0;
  return s;
}

// Adds the 4 x 4 bending block `b` (DOF order w1, theta1, w2, theta2 of the
// v-theta_z plane) at the local DOFs `at`, with the signs `sign` (the w-theta_y
// plane has theta_y = -dw/dx: its rotations enter with -1).
void PlaceBending(Matrix12& target, const Eigen::Matrix4d& b, const int (&at)[4], const double (&sign)[4]) {
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) target(at[i], at[j]) += sign[i] * sign[j] * b(i, j);
}

void PlaceBar(Matrix12& target, double diagonal, double off, int a, int b) {
  target(a, a) += diagonal;
  target(b, b) += diagonal;
  target(a, b) += off;
  target(b, a) += off;
}

// Local stiffness and consistent mass of one element of length l.
void ElementMatrices(const TubeSection& s, double l, Matrix12& k, Matrix12& m) {
  k.setZero();
  m.setZero();
  const double ea = s.e_pa * s.AreaM2(), gj = s.g_pa * s.TorsionM4();
  const double ei_v = s.e_pa * s.IVerticalM4(), ei_l = s.e_pa * s.ILateralM4();
  const double rho_a = s.MassPerLengthKgM();
  const double rho_ip = s.density_kg_m3 * (s.IVerticalM4() + s.ILateralM4());
  PlaceBar(k, ea / l, -ea / l, 0, 6);
  PlaceBar(k, gj / l, -gj / l, 3, 9);
  PlaceBar(m, rho_a * l / 3, rho_a * l / 6, 0, 6);
  PlaceBar(m, rho_ip * l / 3, rho_ip * l / 6, 3, 9);
  const auto bending_k = [l](double ei) {
    Eigen::Matrix4d b;
    b << 12, 6 * l, -12, 6 * l,  //
        6 * l, 4 * l * l, -6 * l, 2 * l * l,  //
        -12, -6 * l, 12, -6 * l,  //
        6 * l, 2 * l * l, -6 * l, 4 * l * l;
    return Eigen::Matrix4d(b * (ei / (l * l * l)));
  };
  Eigen::Matrix4d bm;
  bm << 156, 22 * l, 54, -13 * l,  //
      22 * l, 4 * l * l, 13 * l, -3 * l * l,  //
      54, 13 * l, 156, -22 * l,  //
      -13 * l, -3 * l * l, -22 * l, 4 * l * l;
  bm *= rho_a * l / 420;
  const int lateral[4] = {1, 5, 7, 11}, vertical[4] = {2, 4, 8, 10};
  const double plus[4] = {1, 1, 1, 1}, minus[4] = {1, -1, 1, -1};
  PlaceBending(k, bending_k(ei_l), lateral, plus);
  PlaceBending(k, bending_k(ei_v), vertical, minus);
  PlaceBending(m, bm, lateral, plus);
  PlaceBending(m, bm, vertical, minus);
}

// Rows: the local axes in global coordinates. Local z is the global z for a
// member not along z (the section's height stays vertical), else global x.
Eigen::Matrix3d LocalAxes(const Eigen::Vector3d& along) {
  const Eigen::Vector3d ex = along.normalized();
  Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
  if (std::abs(ex.dot(up)) > 0.999) up = Eigen::Vector3d::UnitX();
  const Eigen::Vector3d ey = up.cross(ex).normalized();
  const Eigen::Vector3d ez = ex.cross(ey);
  Eigen::Matrix3d r;
  r.row(0) = ex;
  r.row(1) = ey;
  r.row(2) = ez;
  return r;
}

int FindOrAddNode(std::vector<Eigen::Vector3d>& nodes, const Eigen::Vector3d& p) {
  for (std::size_t i = 0; i < nodes.size(); ++i)
    if ((nodes[i] - p).norm() < 1e-9) return static_cast<int>(i);
  nodes.push_back(p);
  return static_cast<int>(nodes.size()) - 1;
}

Matrix6 RigidOffset6(const Eigen::Vector3d& c) {
  Matrix6 t = Matrix6::Identity();
  t.block<3, 3>(0, 3) = -Skew(c);
  return t;
}

std::string Format(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.9g", v == 0.0 ? 0.0 : v);  // no "-0"
  return buf;
}

void WriteShapeFile(const std::string& path, const std::string& comment, const std::vector<std::string>& names,
                    const Eigen::MatrixXd& values) {
  std::ostringstream os;
  os << comment << "dof";
  for (Eigen::Index k = 0; k < values.cols(); ++k) os << ", mode" << (k + 1);
  os << '\n';
  for (Eigen::Index r = 0; r < values.rows(); ++r) {
    const double floor = 1e-9 * values.row(r).cwiseAbs().maxCoeff();
    os << names[static_cast<std::size_t>(r)];
    for (Eigen::Index k = 0; k < values.cols(); ++k) {
      const double v = values(r, k);
      os << ", " << Format(std::abs(v) < floor ? 0.0 : v);
    }
    os << '\n';
  }
  std::ofstream f(path, std::ios::binary);
  f << os.str();
  if (!f.flush()) throw std::runtime_error("cannot write " + path);
}

}  // namespace

double TubeSection::AreaM2() const {
  return width_m * height_m - (width_m - 2 * wall_m) * (height_m - 2 * wall_m);
}

double TubeSection::IVerticalM4() const {
  const double bi = width_m - 2 * wall_m, hi = height_m - 2 * wall_m;
  return (width_m * std::pow(height_m, 3) - bi * std::pow(hi, 3)) / 12;
}

double TubeSection::ILateralM4() const {
  const double bi = width_m - 2 * wall_m, hi = height_m - 2 * wall_m;
  return (height_m * std::pow(width_m, 3) - hi * std::pow(bi, 3)) / 12;
}

double TubeSection::TorsionM4() const {
  // J = 4 A_m^2 t / s_m, A_m and s_m the area and perimeter of the wall's mid-line.
  const double bm = width_m - wall_m, hm = height_m - wall_m;
  return 4 * (bm * hm) * (bm * hm) * wall_m / (2 * (bm + hm));
}

int FeModel::NodeAt(const Eigen::Vector3d& position_m) const {
  for (std::size_t i = 0; i < nodes_m.size(); ++i)
    if ((nodes_m[i] - position_m).norm() < 1e-9) return static_cast<int>(i);
  std::ostringstream os;
  os << "no node at (" << position_m.x() << ", " << position_m.y() << ", " << position_m.z() << ") m";
  throw std::runtime_error(os.str());
}

Eigen::Matrix<double, 3, 6> RigidOffset(const Eigen::Vector3d& offset_m) {
  return RigidOffset6(offset_m).topRows<3>();
}

FeModel Assemble(const FrameDescription& frame) {
  FeModel model;
  struct Element {
    int a, b;
    Eigen::Matrix3d axes;
    double length_m;
  };
  std::vector<Element> elements;
  for (const Member& member : frame.members) {
    const Eigen::Vector3d along = member.to_m - member.from_m;
    if (!(along.norm() > 1e-9)) throw std::runtime_error("a member of zero length");
    if (member.elements < 1) throw std::runtime_error("a member needs at least one element");
    const Eigen::Matrix3d axes = LocalAxes(along);
    int previous = FindOrAddNode(model.nodes_m, member.from_m);
    for (int e = 1; e <= member.elements; ++e) {
      const Eigen::Vector3d p = member.from_m + along * (static_cast<double>(e) / member.elements);
      const int next = FindOrAddNode(model.nodes_m, p);
      elements.push_back({previous, next, axes, along.norm() / member.elements});
      previous = next;
    }
  }
  const int n = 6 * static_cast<int>(model.nodes_m.size());
  model.k = Eigen::MatrixXd::Zero(n, n);
  model.m = Eigen::MatrixXd::Zero(n, n);
  for (const Element& e : elements) {
    Matrix12 kl, ml, t = Matrix12::Zero();
    ElementMatrices(frame.section, e.length_m, kl, ml);
    for (int b = 0; b < 4; ++b) t.block<3, 3>(3 * b, 3 * b) = e.axes;
    const Matrix12 kg = t.transpose() * kl * t, mg = t.transpose() * ml * t;
    const int base[2] = {6 * e.a, 6 * e.b};
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j) {
        model.k.block<6, 6>(base[i], base[j]) += kg.block<6, 6>(6 * i, 6 * j);
        model.m.block<6, 6>(base[i], base[j]) += mg.block<6, 6>(6 * i, 6 * j);
      }
  }
  for (const PointMass& pm : frame.masses) {
    const int node = model.NodeAt(pm.node_m);
    Matrix6 local = Matrix6::Zero();
    local.diagonal() << pm.mass_kg, pm.mass_kg, pm.mass_kg, pm.inertia_kg_m2;
    const Matrix6 t = RigidOffset6(pm.offset_m);
    model.m.block<6, 6>(6 * node, 6 * node) += t.transpose() * local * t;
  }
  for (const Mount& mount : frame.mounts) {
    const int node = model.NodeAt(mount.node_m);
    const Eigen::Matrix<double, 3, 6> t = RigidOffset(mount.offset_m);
    model.k.block<6, 6>(6 * node, 6 * node) += t.transpose() * mount.stiffness_n_m.asDiagonal() * t;
  }
  return model;
}

Eigen::VectorXd RigidTranslation(int nodes, const Eigen::Vector3d& direction) {
  Eigen::VectorXd r = Eigen::VectorXd::Zero(6 * nodes);
  for (int i = 0; i < nodes; ++i) r.segment<3>(6 * i) = direction;
  return r;
}

Modes SolveModes(const FeModel& model, double max_f_hz) {
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(model.k, model.m,
                                                                       Eigen::ComputeEigenvectors | Eigen::Ax_lBx);
  if (eig.info() != Eigen::Success) throw std::runtime_error("the generalised eigenproblem did not converge");
  Modes modes;
  std::vector<Eigen::Index> kept;
  for (Eigen::Index k = 0; k < eig.eigenvalues().size(); ++k) {
    const double f_hz = std::sqrt(std::max(eig.eigenvalues()(k), 0.0)) / kTwoPi;
    if (f_hz > max_f_hz) break;  // ascending
    modes.f_hz.push_back(f_hz);
    kept.push_back(k);
  }
  const Eigen::Index n = model.dofs();
  Eigen::VectorXd weight(n);  // irregular, so that no mode's weighted sum vanishes by symmetry
  for (Eigen::Index i = 0; i < n; ++i) weight(i) = 1.0 + std::sqrt(static_cast<double>(i % 97) + 2.0);
  modes.phi.resize(n, static_cast<Eigen::Index>(kept.size()));
  for (std::size_t c = 0; c < kept.size(); ++c) {
    Eigen::VectorXd v = eig.eigenvectors().col(kept[c]);
    v /= std::sqrt(v.dot(model.m * v));
    if (weight.dot(v) < 0) v = -v;
    modes.phi.col(static_cast<Eigen::Index>(c)) = v;
  }
  return modes;
}

Eigen::RowVectorXd PointRow(const FeModel& model, const Eigen::Vector3d& node_m, const Eigen::Vector3d& offset_m,
                            const Eigen::Vector3d& direction) {
  Eigen::RowVectorXd row = Eigen::RowVectorXd::Zero(model.dofs());
  row.segment<6>(6 * model.NodeAt(node_m)) = direction.transpose() * RigidOffset(offset_m);
  return row;
}

Eigen::RowVectorXd RelativeRow(const FeModel& model, const Eigen::Vector3d& point_node_m,
                               const Eigen::Vector3d& reference_node_m, const Eigen::Vector3d& offset_m,
                               const Eigen::Vector3d& direction) {
  // e = u_p - u_r - theta_r x (p - r), and d . (theta x a) = theta . (a x d).
  const Eigen::Vector3d arm = point_node_m - reference_node_m;
  Eigen::RowVectorXd row = PointRow(model, point_node_m, offset_m, direction) -
                           PointRow(model, reference_node_m, offset_m, direction);
  row.segment<3>(6 * model.NodeAt(reference_node_m) + 3) -= arm.cross(direction).transpose();
  return row;
}

// ---------------------------------------------------------------------------

MetrologyFrameLayout MetrologyLayout(const MetrologyFrameParameters& p) {
  MetrologyFrameLayout l;
  l.head_m = {0.75 * p.length_m, 0, 0};
  l.reference_m = {0.5 * p.length_m, 0, 0};
  l.stage_m = {0.25 * p.length_m, -0.5 * p.width_m, 0};
  for (double x : {0.0, p.length_m})
    for (double y : {-0.5 * p.width_m, 0.5 * p.width_m}) l.isolators_m.push_back({x, y, 0});
  return l;
}

FrameDescription MetrologyFrame(const MetrologyFrameParameters& p) {
  if (p.cross_members < 5 || (p.cross_members - 1) % 4 != 0 || p.rails < 3 || p.rails % 2 != 1)
    throw std::runtime_error("cross_members must be 4 n + 1 and rails odd, at least 3 (joints under the head, "
                             "the reference and the stage)");
  FrameDescription f;
  f.section = p.section;
  const int bays = p.cross_members - 1;
  const double bay_m = p.length_m / bays, half_width_m = 0.5 * p.width_m;
  const auto elements = [&](double length_m) {
    return std::max(2, 2 * static_cast<int>(std::lround(0.5 * length_m / p.element_length_m)));
  };
  // Rails along x (the sides, the centre line and any between), cut at the cross members.
  const int rail_gaps = p.rails - 1;
  const double rail_pitch_m = p.width_m / rail_gaps;
  for (int r = 0; r < p.rails; ++r)
    for (int b = 0; b < bays; ++b) {
      const double y = -half_width_m + r * rail_pitch_m;
      f.members.push_back({{b * bay_m, y, 0}, {(b + 1) * bay_m, y, 0}, elements(bay_m)});
    }
  // Cross members along y, cut at the rails.
  for (int c = 0; c < p.cross_members; ++c)
    for (int r = 0; r < rail_gaps; ++r) {
      const double x = c * bay_m, y = -half_width_m + r * rail_pitch_m;
      f.members.push_back({{x, y, 0}, {x, y + rail_pitch_m, 0}, elements(rail_pitch_m)});
    }
  const MetrologyFrameLayout l = MetrologyLayout(p);
  // Payloads as solid blocks: the head 0.2 x 0.2 x 0.3 m, the reference
  // 0.2 x 0.2 x 0.2 m, the stator 0.4 x 0.2 x 0.1 m (I = m (a^2 + b^2) / 12).
  const auto block = [](double m, double a, double b, double c) {
    return Eigen::Vector3d(m * (b * b + c * c) / 12, m * (a * a + c * c) / 12, m * (a * a + b * b) / 12);
  };
  f.masses.push_back({l.head_m, {0, 0, -p.head_cog_depth_m}, p.head_mass_kg, block(p.head_mass_kg, 0.2, 0.2, 0.3)});
  f.masses.push_back({l.reference_m, {0, 0, -p.reference_cog_depth_m}, p.reference_mass_kg,
                      block(p.reference_mass_kg, 0.2, 0.2, 0.2)});
  f.masses.push_back({l.stage_m, {0, 0, -p.stator_cog_depth_m}, p.stator_mass_kg,
                      block(p.stator_mass_kg, 0.4, 0.2, 0.1)});
  const double m_total = TotalMassKg(f);
  const double k_z = m_total * std::pow(kTwoPi * p.isolator_vertical_hz, 2) / 4;
  const double k_xy = m_total * std::pow(kTwoPi * p.isolator_lateral_hz, 2) / 4;
  for (const Eigen::Vector3d& at : l.isolators_m)
    f.mounts.push_back({at, {0, 0, -p.isolator_depth_m}, {k_xy, k_xy, k_z}});
  return f;
}

double TotalMassKg(const FrameDescription& frame) {
  double m = 0;
  for (const Member& member : frame.members)
    m += frame.section.MassPerLengthKgM() * (member.to_m - member.from_m).norm();
  for (const PointMass& pm : frame.masses) m += pm.mass_kg;
  return m;
}

ModalTables MetrologyTables(const MetrologyFrameParameters& p, const FeModel& model, const Modes& modes) {
  const MetrologyFrameLayout l = MetrologyLayout(p);
  const Eigen::Vector3d ux = Eigen::Vector3d::UnitX(), uz = Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d zero = Eigen::Vector3d::Zero(), depth(0, 0, -p.measurement_depth_m);
  ModalTables t;
  t.f_hz = modes.f_hz;
  for (double f : modes.f_hz) t.zeta.push_back(f < p.isolation_band_hz ? p.zeta_isolation : p.zeta_structure);
  const Eigen::Index n = static_cast<Eigen::Index>(modes.f_hz.size());

  t.stage_names = {"stage_fx", "stage_fz"};
  t.stage.resize(2, n);
  t.stage.row(0) = PointRow(model, l.stage_m, zero, ux) * modes.phi;
  t.stage.row(1) = PointRow(model, l.stage_m, zero, uz) * modes.phi;

  t.floor_names = {"floor_x", "floor_z"};
  t.floor.resize(2, n);
  const int nodes = static_cast<int>(model.nodes_m.size());
  t.floor.row(0) = -(modes.phi.transpose() * (model.m * RigidTranslation(nodes, ux))).transpose();
  t.floor.row(1) = -(modes.phi.transpose() * (model.m * RigidTranslation(nodes, uz))).transpose();

  t.output_names = {"head_x", "head_z"};
  t.output.resize(2, n);
  t.output.row(0) = RelativeRow(model, l.head_m, l.reference_m, depth, ux) * modes.phi;
  t.output.row(1) = RelativeRow(model, l.head_m, l.reference_m, depth, uz) * modes.phi;
  return t;
}

std::string DescribeParameters(const MetrologyFrameParameters& p, const FrameDescription& frame) {
  const TubeSection& s = p.section;
  const MetrologyFrameLayout l = MetrologyLayout(p);
  std::ostringstream os;
  os << "frame " << p.length_m << " m x " << p.width_m << " m: " << p.rails << " rails along x, " << p.cross_members
     << " cross members, elements of about " << p.element_length_m << " m\n"
     << "tube " << s.width_m * 1e3 << " x " << s.height_m * 1e3 << " x " << s.wall_m * 1e3
     << " mm (width x height x wall), E " << s.e_pa / 1e9 << " GPa, G " << s.g_pa / 1e9 << " GPa, rho "
     << s.density_kg_m3 << " kg/m^3\n"
     << "sensor head " << p.head_mass_kg << " kg at (" << l.head_m.x() << ", " << l.head_m.y() << ") m, centre of mass "
     << p.head_cog_depth_m << " m below; reference " << p.reference_mass_kg << " kg at (" << l.reference_m.x() << ", "
     << l.reference_m.y() << ") m, " << p.reference_cog_depth_m << " m below; measurement points "
     << p.measurement_depth_m << " m below\n"
     << "stage stator " << p.stator_mass_kg << " kg at (" << l.stage_m.x() << ", " << l.stage_m.y() << ") m, "
     << p.stator_cog_depth_m << " m below; the stage forces act at the node\n"
     << "total mass " << TotalMassKg(frame) << " kg on 4 isolators at the corners, " << p.isolator_depth_m
     << " m below: " << p.isolator_vertical_hz << " Hz vertical, " << p.isolator_lateral_hz
     << " Hz lateral (whole mass)\n"
     << "damping ratio " << p.zeta_isolation << " below " << p.isolation_band_hz << " Hz (isolation modes), "
     << p.zeta_structure << " above; modes up to " << p.max_frequency_hz << " Hz\n";
  return os.str();
}

void WriteTables(const ModalTables& t, const std::string& dir, const std::string& comment) {
  std::string header;
  std::istringstream lines(comment);
  for (std::string line; std::getline(lines, line);) header += line.empty() ? "#\n" : "# " + line + "\n";
  {
    std::ostringstream os;
    os << header << "mode, f_hz, zeta\n";
    for (std::size_t k = 0; k < t.f_hz.size(); ++k)
      os << (k + 1) << ", " << Format(t.f_hz[k]) << ", " << Format(t.zeta[k]) << '\n';
    const std::string path = dir + "/modes.csv";
    std::ofstream f(path, std::ios::binary);
    f << os.str();
    if (!f.flush()) throw std::runtime_error("cannot write " + path);
  }
  WriteShapeFile(dir + "/phi_in_stage.csv", header, t.stage_names, t.stage);
  WriteShapeFile(dir + "/phi_in_floor.csv", header, t.floor_names, t.floor);
  WriteShapeFile(dir + "/phi_out.csv", header, t.output_names, t.output);
}

}  // namespace deb::frame
