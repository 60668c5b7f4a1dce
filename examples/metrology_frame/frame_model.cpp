// deb-frame-model: the finite-element model behind budgets/metrology_frame.yaml,
// written as deb's modal tables.
//
//   deb-frame-model OUTPUT_DIR      (writes OUTPUT_DIR/modes.csv, phi_in_stage.csv,
//                                    phi_in_floor.csv, phi_out.csv; creates OUTPUT_DIR)
//
// The shipped tables are this program's output, byte for byte
// (frame_fe_test.cpp checks it): regenerate them with
//   build/bin/deb-frame-model budgets/metrology_frame
//
// The structure (frame_fe.h; parameters in MetrologyFrameParameters):
// a metrology frame of 2 m x 1 m in the horizontal plane, a grid of five
// aluminium rails along x (0.25 m apart) and nine cross members along y
// (0.25 m apart), all one rectangular tube 80 x 120 x 6 mm (width x height x
// wall), 3-D Euler-Bernoulli frame elements of 62.5 mm (6 DOFs per node,
// 1638 DOFs), rigid joints. On it: an optical sensor head (12 kg) on the
// centre rail at x = 1.5 m, the reference it is measured against (a
// reference block, 8 kg) at the frame's centre (1.0, 0) m, and the stator of
// a stage (20 kg) on a side rail at (0.5, -0.5) m, each a rigid block with
// its centre of mass below the frame. Four passive isolators under the
// corners, their springs 0.10 m below the neutral axis, tuned so that the
// whole mass (156 kg) would bounce at 3 Hz vertically and sway at 2.5 Hz
// laterally. A consistent mass matrix M, the stiffness K (members and
// isolator springs), and the modes of K phi = w^2 M phi up to 5 kHz (Eigen's
// GeneralizedSelfAdjointEigenSolver): 180 modes, six isolation modes at
// 2.5-5.4 Hz (sway y, sway x, bounce, yaw, roll, pitch), then the frame's
// own from 96 Hz (twist) and 121 Hz (bending along x).
//
// Modal coordinates. Each mode is mass-normalised, phi^T M phi = 1, so Phi is
// in 1/sqrt(kg) and the modal coordinate q = Phi^T M u in sqrt(kg) m; then
// Phi^T K Phi = diag(w_k^2) and, with modal damping,
//   q_k'' + 2 zeta_k w_k q_k' + w_k^2 q_k = phi_k^T f - Gamma_k a_g,
// which is the equation deb's `type: modal` path realises
// (deb/systems/modal_model.h), with phi_in = the input rows below.
//
// Inputs (signs as the model's axes: a positive force or acceleration along
// +x or +z):
//  - phi_in_stage.csv: stage_fx, stage_fz, the shape rows at the stator's
//    node along x and z, in 1/sqrt(kg): a force F [N] there (the stage's
//    reaction on the frame) enters mode k as phi(stage, k) F.
//  - phi_in_floor.csv: floor_x, floor_z, the floor's acceleration a_g under
//    the isolators as an equivalent modal load. In coordinates relative to the
//    floor, u = u_rel + r u_g with r the rigid-body translation along the
//    floor's direction (1 on every translation DOF along it, 0 elsewhere),
//    K r = 0 for the frame and the isolator springs only see u_rel, so
//      M u_rel'' + C u_rel' + K u_rel = f - M r a_g.
//    The modal force is therefore -Gamma_k a_g with the participation factor
//    Gamma = Phi^T M r, in kg / sqrt(kg) = sqrt(kg): the row is -Gamma,
//    with input unit m/s^2. Over all modes sum_k Gamma_k^2 = r^T M r = the
//    total mass; the modes kept hold nearly all of it (printed when run).
//    deb feeds the floor's VC velocity (um/s) into this m/s^2 input by
//    differentiating it (x j 2 pi f; deb/units/unit.h, ConvertUnit), and the
//    floor's own motion drops out of the output (below). Modal damping in relative coordinates gives a mode the
//    transmissibility (w^2 + 2 j zeta w w_k)/(...) of a spring and a dashpot.
//  - deb takes shapes without a unit of their own: a consistent set (m, kg, s)
//    makes phi_out phi_in / w^2 a compliance in m/N and phi_out Gamma / w^2 a
//    displacement per acceleration in s^2 (m per m/s^2).
//
// Outputs (phi_out.csv, in 1/sqrt(kg); output unit m): what the sensor head
// measures against its reference. The stage is servoed to the reference, so
// a rigid motion of the whole frame is followed and is no error; the error is
// the head's displacement relative to the reference in axes that move with
// the reference block (its translation and its tilt),
//   e = u_head - u_ref - theta_ref x (p_head - p_ref),
// of the two measurement points 0.25 m below the neutral axis (a point c
// from a node moves by u + theta x c), a combination of shape rows
// (RelativeRow in frame_fe.h):
//  - head_z, vertical (focus): z_head - z_ref + 0.5 m theta_y,ref,
//  - head_x, horizontal: x_head - x_ref - 0.25 m (theta_y,head - theta_y,ref).
// Every rigid-body motion gives e = 0 (tested), so the floor's own motion,
// which is a rigid translation r u_g, drops out as well: the relative
// coordinate u_rel gives e exactly. The isolation modes reach e through the
// frame's deformation under its own inertia while it rocks on the isolators.
//
// Damping (modal): zeta = 0.05 for the six isolation modes (below 20 Hz):
// damped passive isolators (air mounts with a damping orifice, or elastomer)
// reach 5-10 %, more damping would spoil the isolation above the mounts'
// frequency. zeta = 0.002 for the frame's modes: aluminium itself has a loss
// factor near 1e-4, the bolted joints and mounted payloads bring a frame of
// this kind to 0.1-0.5 %; the lower end is taken, which is the cautious
// figure for a budget.
//
// Limits of the model: Euler-Bernoulli elements without shear deformation
// and section rotary inertia stiffen the modes whose bending half-wave is not
// long against the 120 mm tube (at 5 kHz the half-wave is about 0.2 m); joints
// are rigid points; the payloads are rigid. The modes above 5 kHz are left
// out, and with them their static (residual) compliance.
#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>

#include "examples/metrology_frame/frame_fe.h"

int main(int argc, char** argv) {
  if (argc != 2 || std::string(argv[1]).empty() || argv[1][0] == '-') {
    std::fprintf(stderr,
                 "usage: deb-frame-model OUTPUT_DIR\n"
                 "writes the metrology frame's modal tables (modes.csv, phi_in_stage.csv, phi_in_floor.csv,\n"
                 "phi_out.csv) into OUTPUT_DIR, e.g. budgets/metrology_frame\n");
    return 2;
  }
  try {
    using namespace deb::frame;
    const MetrologyFrameParameters p;
    const FrameDescription frame = MetrologyFrame(p);
    const FeModel model = Assemble(frame);
    const Modes modes = SolveModes(model, p.max_frequency_hz);
    const ModalTables tables = MetrologyTables(p, model, modes);
    const std::string comment =
        "generated by examples/metrology_frame/frame_model.cpp (deb-frame-model); do not edit, regenerate:\n"
        "  build/bin/deb-frame-model budgets/metrology_frame\n" +
        DescribeParameters(p, frame);
    std::filesystem::create_directories(argv[1]);
    WriteTables(tables, argv[1], comment);

    const double m_total = TotalMassKg(frame);
    std::printf("%d DOFs, %zu modes up to %g Hz, total mass %.6g kg\n", model.dofs(), modes.f_hz.size(),
                p.max_frequency_hz, m_total);
    const char* names[2] = {"x", "z"};
    for (int d = 0; d < 2; ++d)
      std::printf("effective mass along %s in the modes kept: %.4f of the total\n", names[d],
                  tables.floor.row(d).squaredNorm() / m_total);
    std::printf("first modes [Hz]:");
    for (std::size_t k = 0; k < modes.f_hz.size() && k < 12; ++k) std::printf(" %.4g", modes.f_hz[k]);
    std::printf("\n");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "deb-frame-model: %s\n", e.what());
    return 1;
  }
  return 0;
}
