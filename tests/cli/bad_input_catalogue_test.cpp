// The bad-input catalogue: every input of the project's reliability audit
// (its case ids: Y budget, W sweep, N sensitivity, S spectrum CSV, T time
// series, F FRF table, M MATLAB .mat file, N Nastran result file, U universal file, C command line, X security-minded) run through the deb binary, one fresh
// directory per case. Each case states the
// exit code and the form of the first `deb: error:` line (budget errors:
// `b.yaml:LINE:COL: KEY.PATH: ...`), and for every case that fails, that the
// directory is exactly as it was: nothing new (not even an empty reports/),
// nothing changed, nothing deleted.
//
// Ids with a suffix (Y00p, C25f, ...) are follow-ups of the audit's case;
// ids with a trailing '+' are new cases in the same family. The audit of the
// result store, .mat files and extends adds A (deb report on a crafted
// result.h5), B (.mat), D (extends), E (text) and H (writing) cases, by its
// ids; their stores are what deb run wrote, changed with HDF5 itself.
#include <doctest/doctest.h>
#include <hdf5.h>
#include <matio.h>

#include <sys/wait.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <set>
#include <string>
#include <unistd.h>
#include <utility>
#include <vector>

#include "tests/support/cli_harness.h"
#include "tests/support/op4_writer.h"

namespace fs = std::filesystem;

namespace {

using deb::test::ExitCode;
using deb::test::ReadAll;
using deb::test::TempDir;

// ---------------------------------------------------------------------------
// What a case is.

using Files = std::vector<std::pair<std::string, std::string>>;  // name -> content, written in order

struct Result {
  int exit_code = -1;
  double seconds = 0.0;
  std::string out, err;
};

// Extra assertions for a case; `work` is the case directory. Returns a
// description of what is wrong, or "" when all is well.
using Check = std::string (*)(const fs::path& work, const Result& r);

// The form of the first `deb: error:` line.
struct Where {
  enum Kind { kSuccess, kUsage, kBudget, kFile, kContains } kind = kUsage;
  std::string file;    // kBudget, kFile: the file named first
  std::string marker;  // kBudget: text in `file` at the reported position ('|' marks it); "" = any position
  std::string key;     // kBudget: key path prefix; "" = not checked
  std::string text;    // kContains: text the line holds (e.g. "spec.csv:6:4:")
};

Where Ok() { return {Where::kSuccess, "", "", "", ""}; }
Where Usage() { return {Where::kUsage, "", "", "", ""}; }
// b.yaml:LINE:COL: KEY...: the position of `marker` in b.yaml, the key path starting with `key`.
Where At(const std::string& marker, const std::string& key) { return {Where::kBudget, "b.yaml", marker, key, ""}; }
Where AtIn(const std::string& file, const std::string& marker, const std::string& key) {
  return {Where::kBudget, file, marker, key, ""};
}
// `deb: error: FILE...`: the message starts with the file's name (no position).
Where InFile(const std::string& file) { return {Where::kFile, file, "", "", ""}; }
// The error line holds `text` somewhere (a table position such as "spec.csv:6:4:", or a name).
Where Names(const std::string& text) { return {Where::kContains, "", "", "", text}; }

struct Case {
  std::string id;
  std::string what;
  Files files;
  std::string args;  // the deb command line after `deb` (shell syntax), run in the case directory
  int exit_code;
  Where where;
  std::vector<std::string> says = {};   // stderr holds each of these
  std::vector<std::string> never = {};  // stderr holds none of these
  std::string setup = "";               // shell, in the case directory, before the snapshot ($DEB is deb)
  std::string env = "";                 // VAR=value ... for deb
  double max_seconds = 0;               // 0: only the 60 s timeout
  Check check = nullptr;
};

// ---------------------------------------------------------------------------
// Inputs.

// One flat force source, a 2nd-order transfer function, one output in nm,
// a log grid 1-100 Hz (the audit's base budget).
const std::string kBase = R"Y(name: cat
description: bad-input catalogue base budget
grid: {type: log, min_hz: 1, max_hz: 100, points: 50}
sources:
  - name: noise
    unit: N
    spectrum: {type: flat, level: 1.0e-6}
paths:
  - name: plant
    type: transfer_function
    num: [1]
    den: [1, 2, 100]
    inputs: [u]
    outputs: [y]
    input_unit: N
    output_unit: um
contributors:
  - {name: c1, source: noise, path: plant}
outputs:
  - {name: z, signal: y, unit: nm, rms_max: 5}
)Y";

const std::string kTf = "type: transfer_function\n    num: [1]\n    den: [1, 2, 100]\n";
// The base budget's plant with its channel names, and the same plant as one mass on a spring.
const std::string kPlant = kTf + "    inputs: [u]\n    outputs: [y]\n";
const std::string kMass =
    "type: lumped_masses\n    masses: {m: 1 kg}\n    couplings: [{between: [m, ground], k: 100 N/m, c: 2 N s/m}]\n"
    "    inputs: [{name: u, force: m}]\n    outputs: [{name: y, displacement: m}]\n";
const std::string kSourceBlock = "sources:\n  - name: noise\n    unit: N\n    spectrum: {type: flat, level: 1.0e-6}\n";

// `text` with the first `from` replaced by `to` (which must be there).
std::string Sub(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  if (at == std::string::npos) {
    std::fprintf(stderr, "catalogue: substitution '%s' not found\n", from.c_str());
    std::abort();
  }
  return text.replace(at, from.size(), to);
}

Files Budget(const std::string& text) { return {{"b.yaml", text}}; }
Files B() { return Budget(kBase); }
Files B(const std::string& from, const std::string& to) { return Budget(Sub(kBase, from, to)); }
Files B(const std::string& f1, const std::string& t1, const std::string& f2, const std::string& t2) {
  return Budget(Sub(Sub(kBase, f1, t1), f2, t2));
}
Files With(Files files, const std::string& name, const std::string& content) {
  files.emplace_back(name, content);
  return files;
}

// Measured spectrum source reading spec.csv (0.5-200 Hz, 1e-6 N^2/Hz).
const std::string kMeasured = Sub(kBase, "{type: flat, level: 1.0e-6}", "{type: measured, file: spec.csv}");
const std::string kSpec =
    "f_hz,z\n0.5,1e-6\n1,1e-6\n2,1e-6\n5,1e-6\n10,1e-6\n20,1e-6\n50,1e-6\n100,1e-6\n200,1e-6\n";
const std::string kSpecRows = "0.5,1e-6\n1,1e-6\n2,1e-6\n5,1e-6\n10,1e-6\n20,1e-6\n50,1e-6\n100,1e-6\n200,1e-6\n";
const std::string kBom = "\xEF\xBB\xBF";
Files M(const std::string& spec) { return {{"b.yaml", kMeasured}, {"spec.csv", spec}}; }
Files M(const std::string& from, const std::string& to, const std::string& spec) {
  return {{"b.yaml", Sub(kMeasured, from, to)}, {"spec.csv", spec}};
}
std::string SpecSub(const std::string& from, const std::string& to) { return Sub(kSpec, from, to); }
std::string Replace(std::string s, char from, char to) {
  for (char& c : s) c = c == from ? to : c;
  return s;
}
Where AtSpecFile() { return At("file: |spec.csv", "sources[0].spectrum.file"); }

// Time-series source: a recording read by Welch at load; the grid 5-400 Hz
// lies inside its bins (1000 Hz, default segments of 512 samples).
const std::string kTsBase = Sub(kBase, "min_hz: 1, max_hz: 100", "min_hz: 5, max_hz: 400");
std::string Ts(const std::string& spectrum) { return Sub(kTsBase, "{type: flat, level: 1.0e-6}", spectrum); }
const std::string kTs = Ts("{type: timeseries, file: rec.csv}");
const std::string kRaw = Ts("{type: timeseries, file: rec.raw, format: float64, rate_hz: 1000, file_channels: 1}");

// Deterministic white noise in [-1, 1].
std::vector<double> Noise(int n, std::uint64_t seed) {
  std::vector<double> v;
  std::uint64_t s = seed * 6364136223846793005ULL + 1442695040888963407ULL;
  for (int i = 0; i < n; ++i) {
    s = s * 6364136223846793005ULL + 1442695040888963407ULL;
    v.push_back(static_cast<double>(s >> 11) / 9007199254740992.0 * 2.0 - 1.0);
  }
  return v;
}
std::string Num(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.9g", v);
  return b;
}
// One channel x at 1000 Hz, `n` samples scaled by `scale`.
std::string RecCsv(int n = 4096, double scale = 1.0) {
  std::string s = "# rate_hz: 1000\nx\n";
  for (double v : Noise(n, 1)) s += Num(scale * v) + "\n";
  return s;
}
// A time column t (first data row on line 2), `n` samples; `t_of(i)` the stamps.
std::string RecTimed(int n, const std::function<double(int)>& t_of) {
  std::string s = "t,x\n";
  const auto x = Noise(n, 2);
  for (int i = 0; i < n; ++i) s += Num(t_of(i)) + "," + Num(x[static_cast<std::size_t>(i)]) + "\n";
  return s;
}
// Three co-located sensors (common motion plus independent noise), named as given.
std::string Rec3(const std::string& header) {
  std::string s = "# rate_hz: 1000\n# unit: um/s\n" + header + "\n";
  const auto u = Noise(4096, 3), e1 = Noise(4096, 4), e2 = Noise(4096, 5), e3 = Noise(4096, 6);
  for (std::size_t i = 0; i < u.size(); ++i)
    s += Num(u[i] + 0.1 * e1[i]) + "," + Num(u[i] + 0.1 * e2[i]) + "," + Num(u[i] + 0.2 * e3[i]) + "\n";
  return s;
}
// A shaker input F and a response x (a short FIR filter of F plus a little noise).
std::string RecFrf(const std::string& header) {
  std::string s = "# rate_hz: 1000\n" + header + "\n";
  const auto f = Noise(4096, 7), e = Noise(4096, 8);
  for (std::size_t i = 0; i < f.size(); ++i)
    s += Num(f[i]) + "," + Num(0.5 * f[i] + 0.3 * (i > 0 ? f[i - 1] : 0.0) + 0.01 * e[i]) + "\n";
  return s;
}
// Raw little-endian float64 samples (this host is little-endian, as deb requires).
std::string RawF64(const std::vector<double>& v) {
  std::string s(v.size() * sizeof(double), '\0');
  if (!v.empty()) std::memcpy(&s[0], v.data(), s.size());
  return s;
}
std::string RawWithNan() {
  auto v = Noise(4096, 9);
  v[100] = std::nan("");
  return RawF64(v);
}

// A measured FRF path reading frf.csv (0.5-200 Hz, |H| = 0.01 um/N).
const std::string kFrf = Sub(kBase, "type: transfer_function\n    num: [1]\n    den: [1, 2, 100]\n    inputs: [u]\n"
                                    "    outputs: [y]\n",
                             "type: frf\n    file: frf.csv\n");
const std::string kFrfTable =
    "f_hz, y/u.mag, y/u.phase_deg\n0.5, 0.01, 0\n1, 0.01, -1\n2, 0.01, -2\n5, 0.01, -5\n10, 0.01, -10\n"
    "20, 0.01, -20\n50, 0.01, -50\n100, 0.01, -100\n200, 0.01, -150\n";
Files Fr(const std::string& table) { return {{"b.yaml", kFrf}, {"frf.csv", table}}; }
Where AtFrfFile() { return At("file: |frf.csv", "paths[0].file"); }

// The base plant 1/(s^2 + 2 s + 100) as a state space read from plant.mat.
const std::string kMat = Sub(kBase, "type: transfer_function\n    num: [1]\n    den: [1, 2, 100]\n",
                             "type: state_space\n    file: plant.mat\n");
// plant.mat: A, B (unless !with_b) and C of that plant, written by matio (compressed version 5).
std::string PlantMat(bool with_b = true) {
  const fs::path dir = TempDir("catalogue_mat"), tmp = dir / "plant.mat";
  mat_t* mat = Mat_CreateVer(tmp.c_str(), nullptr, MAT_FT_MAT5);
  if (mat == nullptr) std::abort();
  auto put = [&](const char* name, std::vector<double> v, std::size_t rows, std::size_t cols) {
    std::size_t dims[2] = {rows, cols};
    matvar_t* var = Mat_VarCreate(name, MAT_C_DOUBLE, MAT_T_DOUBLE, 2, dims, v.data(), 0);
    if (var == nullptr || Mat_VarWrite(mat, var, MAT_COMPRESSION_ZLIB) != 0) std::abort();
    Mat_VarFree(var);
  };
  put("A", {0, -100, 1, -2}, 2, 2);  // columns first: [0 1; -100 -2]
  if (with_b) put("B", {0, 1}, 2, 1);
  put("C", {1, 0}, 1, 2);
  if (Mat_Close(mat) != 0) std::abort();
  std::ifstream in(tmp, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  fs::remove_all(dir);
  return bytes;
}
Where AtMatFile() { return At("file: |plant.mat", "paths[0].file"); }

// The base budget's plant as modes from a Nastran OP2 file: the beam that
// Nastran wrote (tests/data/nastran), its tip force to its tip motion.
const std::string kNastran =
    Sub(kBase, "type: transfer_function\n    num: [1]\n    den: [1, 2, 100]\n    inputs: [u]\n    outputs: [y]\n",
        "type: modal\n    file: beam.op2\n    inputs: {u: \"11:T3\"}\n    outputs: {y: \"11:T3\"}\n"
        "    damping: 0.005\n    length_unit: in\n    force_unit: lbf\n");
std::string BeamOp2() { return ReadAll(fs::path(DEB_SOURCE_DIR) / "tests/data/nastran/beam_modes_m1.op2"); }
Files Op2(const std::string& bytes, const std::string& budget = kNastran) { return {{"b.yaml", budget}, {"beam.op2", bytes}}; }
// The OP2 with its bytes [at, at + with.size()) replaced.
std::string Op2With(std::size_t at, const std::string& with) { return BeamOp2().replace(at, with.size(), with); }
Where AtOp2File() { return At("file: |beam.op2", "paths[0].file"); }

// The base budget's plant as one mode from OP4 matrices (a mass of 1 kg on
// 100 N/m: the base's 1 / (s^2 + 2 s + 100) with 10 % damping).
const std::string kOp4Modal =
    Sub(kBase, "type: transfer_function\n    num: [1]\n    den: [1, 2, 100]\n    inputs: [u]\n    outputs: [y]\n",
        "type: modal\n    file: m.op4\n    matrices: {phi: PHIG, lambda: LAMA}\n    rows: [\"1:T1\"]\n"
        "    inputs: {u: \"1:T1\"}\n    outputs: {y: \"1:T1\"}\n    damping: 0.1\n    length_unit: m\n");
std::string ModesOp4() {
  return deb::test::TextOp4({{"PHIG", Eigen::MatrixXd::Ones(1, 1)}, {"LAMA", Eigen::MatrixXd::Constant(1, 1, 100.0)}});
}
Files Op4Modal(const std::string& bytes, const std::string& budget = kOp4Modal) {
  return {{"b.yaml", budget}, {"m.op4", bytes}};
}
Where AtOp4Matrices() { return At("matrices: |{phi", "paths[0].matrices"); }

// The base budget with its source's level an uncertain parameter.
const std::string kUncertain =
    Sub(Sub(kBase, "description: bad-input catalogue base budget\n",
            "description: bad-input catalogue base budget\nparameters:\n"
            "  lvl: {value: 1, distribution: {uniform: {min: 0.5, max: 2}}}\n"),
        "level: 1.0e-6", "level: lvl * 1.0e-6");

// The base budget with its plant's stiffness a design variable (den 1, 2, k).
const std::string kOptimise =
    Sub(Sub(kBase, "description: bad-input catalogue base budget\n",
            "description: bad-input catalogue base budget\nparameters:\n"
            "  k: {value: 100, min: 50, max: 400}\n  c: 2\n"),
        "den: [1, 2, 100]", "den: [1, c, k]");

// The base budget's source as the PSD of a universal file a vibration
// controller wrote (tests/data/uff: g^2/Hz, 0-3200 Hz), in m/s^2 through the plant.
const std::string kUff =
    Sub(Sub(Sub(kBase, "unit: N\n    spectrum: {type: flat, level: 1.0e-6}",
                "unit: m/s^2\n    spectrum: {type: measured, file: psd.uff}"),
            "input_unit: N", "input_unit: m/s^2"),
        "rms_max: 5", "rms_max: 5e9");
std::string PsdUff() { return ReadAll(fs::path(DEB_SOURCE_DIR) / "tests/data/uff/sample_dataset58_psd.uff"); }
Files Uff(const std::string& bytes) { return {{"b.yaml", kUff}, {"psd.uff", bytes}}; }
Where AtUffFile() { return At("file: |psd.uff", "sources[0].spectrum.file"); }

// ---------------------------------------------------------------------------
// Result stores (deb report RESULT_DIR) and version 7.3 .mat files, changed
// with HDF5 itself from what deb writes.

// The base budget with a second output (two outputs of one name, A12d).
const std::string kStoreBudget = kBase + "  - {name: z2, signal: y, unit: nm}\n";

// result.h5 of kStoreBudget, written by the deb under test (made once).
const std::string& BaseStore() {
  static const std::string bytes = [] {
    const fs::path dir = TempDir("catalogue_store");
    std::ofstream(dir / "b.yaml") << kStoreBudget;
    const std::string cmd = "cd " + dir.string() + " && " + DEB_BINARY + " run b.yaml -q --no-plots --out r > /dev/null 2>&1";
    if (std::system(cmd.c_str()) != 0) std::abort();
    std::string s = ReadAll(dir / "r" / "result.h5");
    fs::remove_all(dir);
    return s;
  }();
  return bytes;
}

// `bytes` (an HDF5 file) after `change` on it, opened read-write.
std::string ChangedHdf5(const std::string& bytes, const std::function<void(hid_t)>& change) {
  const fs::path dir = TempDir("catalogue_h5"), file = dir / "f.h5";
  std::ofstream(file, std::ios::binary) << bytes;
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  if (f < 0) std::abort();
  change(f);
  if (H5Fclose(f) < 0) std::abort();
  std::string out = ReadAll(file);
  fs::remove_all(dir);
  return out;
}

// A report directory r/ whose store is BaseStore() changed by `change`.
Files Store(const std::function<void(hid_t)>& change) {
  return {{"r/result.h5", ChangedHdf5(BaseStore(), change)},
          {"r/.deb-output", "written by deb; deb replaces this directory on its next run\n"}};
}

// Object `o` of file `f` replaced by a dataset of `type` and `space` made
// with `create` (written from `data` unless it is null).
void Put(hid_t f, const char* o, hid_t type, hid_t space, hid_t create = H5P_DEFAULT, const void* data = nullptr,
         hid_t memory_type = -1) {
  if (H5Lexists(f, o, H5P_DEFAULT) > 0 && H5Ldelete(f, o, H5P_DEFAULT) < 0) std::abort();
  const hid_t d = H5Dcreate2(f, o, type, space, H5P_DEFAULT, create, H5P_DEFAULT);
  if (d < 0) std::abort();
  if (data != nullptr && H5Dwrite(d, memory_type < 0 ? type : memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0)
    std::abort();
  H5Dclose(d);
  H5Sclose(space);
}
hid_t Space(std::vector<hsize_t> dims) {
  return dims.empty() ? H5Screate(H5S_SCALAR) : H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr);
}
void PutNumbers(hid_t f, const char* o, const std::vector<double>& v) {
  Put(f, o, H5T_IEEE_F64LE, Space({v.size()}), H5P_DEFAULT, v.empty() ? nullptr : v.data(), H5T_NATIVE_DOUBLE);
}
void PutNumber(hid_t f, const char* o, double v) { Put(f, o, H5T_IEEE_F64LE, Space({}), H5P_DEFAULT, &v, H5T_NATIVE_DOUBLE); }
void PutText(hid_t f, const char* o, const std::string& text) {
  const hid_t type = H5Tcopy(H5T_C_S1);
  H5Tset_size(type, H5T_VARIABLE);
  H5Tset_cset(type, H5T_CSET_UTF8);
  const char* p = text.c_str();
  Put(f, o, type, Space({}), H5P_DEFAULT, &p);
  H5Tclose(type);
}
void PutFixedText(hid_t f, const char* o, const std::string& text) {
  const hid_t type = H5Tcopy(H5T_C_S1);
  H5Tset_size(type, text.size());
  Put(f, o, type, Space({}), H5P_DEFAULT, text.data());
  H5Tclose(type);
}
// Declared with `dims`, never written.
void PutDeclared(hid_t f, const char* o, std::vector<hsize_t> dims, bool text = false) {
  const hid_t type = H5Tcopy(H5T_C_S1);
  H5Tset_size(type, H5T_VARIABLE);
  Put(f, o, text ? type : H5T_IEEE_F64LE, Space(std::move(dims)));
  H5Tclose(type);
}
// Its type and shape kept, its values in `target` (HDF5 external storage).
void PutExternal(hid_t f, const char* o, const std::string& target) {
  const hid_t d = H5Dopen2(f, o, H5P_DEFAULT);
  if (d < 0) std::abort();
  const hid_t type = H5Dget_type(d), space = H5Dget_space(d);
  const hsize_t bytes = static_cast<hsize_t>(H5Sget_simple_extent_npoints(space)) * H5Tget_size(type);
  H5Dclose(d);
  const hid_t create = H5Pcreate(H5P_DATASET_CREATE);
  if (H5Pset_external(create, target.c_str(), 0, bytes) < 0) std::abort();
  Put(f, o, type, space, create);
  H5Pclose(create);
  H5Tclose(type);
}
void PutExternalLink(hid_t f, const char* o, const char* file, const char* target) {
  if (H5Ldelete(f, o, H5P_DEFAULT) < 0 || H5Lcreate_external(file, target, f, o, H5P_DEFAULT, H5P_DEFAULT) < 0)
    std::abort();
}
void PutSoftLink(hid_t f, const char* o, const char* target) {
  if (H5Ldelete(f, o, H5P_DEFAULT) < 0 || H5Lcreate_soft(target, f, o, H5P_DEFAULT, H5P_DEFAULT) < 0) std::abort();
}
// A virtual dataset of `n` doubles taken from `object` of `file`.
void PutVirtual(hid_t f, const char* o, hsize_t n, const char* file, const char* object) {
  const hid_t create = H5Pcreate(H5P_DATASET_CREATE), source = Space({n});
  if (H5Pset_virtual(create, source, file, object, source) < 0) std::abort();
  Put(f, o, H5T_IEEE_F64LE, Space({n}), create);
  H5Pclose(create);
  H5Sclose(source);
}

// The store with the 8-byte size of the global heap entry holding `text`
// (unique in the file) made to claim 2 GB.
Files DamagedHeapStore(const std::string& text) {
  std::string bytes = BaseStore();
  const std::size_t at = bytes.find(text);
  if (at == std::string::npos || at < 8 || bytes.find(text, at + 1) != std::string::npos) std::abort();
  bytes.replace(at - 8, 8, std::string("\xff\xff\xff\x7f\0\0\0\0", 8));
  return {{"r/result.h5", bytes}, {"r/.deb-output", "written by deb; deb replaces this directory on its next run\n"}};
}

const std::string kReport = "report r --no-plots";
Where AtStore() { return InFile("r/result.h5"); }

// plant.mat as a version 7.3 (HDF5) file, A changed by `change`.
std::string PlantMat73(const std::function<void(hid_t)>& change) {
  const fs::path dir = TempDir("catalogue_mat73"), tmp = dir / "plant.mat";
  mat_t* mat = Mat_CreateVer(tmp.c_str(), nullptr, MAT_FT_MAT73);
  if (mat == nullptr) std::abort();
  auto put = [&](const char* name, std::vector<double> v, std::size_t rows, std::size_t cols) {
    std::size_t dims[2] = {rows, cols};
    matvar_t* var = Mat_VarCreate(name, MAT_C_DOUBLE, MAT_T_DOUBLE, 2, dims, v.data(), 0);
    if (var == nullptr || Mat_VarWrite(mat, var, MAT_COMPRESSION_NONE) != 0) std::abort();
    Mat_VarFree(var);
  };
  put("A", {0, -100, 1, -2}, 2, 2);
  put("B", {0, 1}, 2, 1);
  put("C", {1, 0}, 1, 2);
  if (Mat_Close(mat) != 0) std::abort();
  std::string bytes = ChangedHdf5(ReadAll(tmp), change);
  fs::remove_all(dir);
  return bytes;
}

// plant.mat written uncompressed, with the byte count of the dimensions of
// its first variable (A, at byte 128) made to claim 2 GB (N17).
std::string PlantMatLongPart() {
  const fs::path dir = TempDir("catalogue_mat5"), tmp = dir / "plant.mat";
  mat_t* mat = Mat_CreateVer(tmp.c_str(), nullptr, MAT_FT_MAT5);
  if (mat == nullptr) std::abort();
  std::size_t dims[2] = {2, 2};
  std::vector<double> a = {0, -100, 1, -2};
  matvar_t* var = Mat_VarCreate("A", MAT_C_DOUBLE, MAT_T_DOUBLE, 2, dims, a.data(), 0);
  if (var == nullptr || Mat_VarWrite(mat, var, MAT_COMPRESSION_NONE) != 0) std::abort();
  Mat_VarFree(var);
  if (Mat_Close(mat) != 0) std::abort();
  std::string bytes = ReadAll(tmp);
  fs::remove_all(dir);
  // tag (8), array flags (16), then the dimensions' tag: type (4), bytes (4).
  if (bytes.size() < 160 || bytes[152] != 5) std::abort();
  bytes.replace(156, 4, std::string("\xf0\xff\xff\x7f", 4));
  return bytes;
}

// plant.mat (uncompressed) whose C is renamed A: two variables of one name.
std::string PlantMatTwiceA() {
  const fs::path dir = TempDir("catalogue_mat2"), tmp = dir / "plant.mat";
  mat_t* mat = Mat_CreateVer(tmp.c_str(), nullptr, MAT_FT_MAT5);
  if (mat == nullptr) std::abort();
  auto put = [&](const char* name, std::vector<double> v, std::size_t rows, std::size_t cols) {
    std::size_t dims[2] = {rows, cols};
    matvar_t* var = Mat_VarCreate(name, MAT_C_DOUBLE, MAT_T_DOUBLE, 2, dims, v.data(), 0);
    if (var == nullptr || Mat_VarWrite(mat, var, MAT_COMPRESSION_NONE) != 0) std::abort();
    Mat_VarFree(var);
  };
  put("A", {0, -100, 1, -2}, 2, 2);
  put("B", {0, 1}, 2, 1);
  put("C", {1, 0}, 1, 2);
  if (Mat_Close(mat) != 0) std::abort();
  std::string bytes = ReadAll(tmp);
  fs::remove_all(dir);
  // The name "C": a small miINT8 element of 1 byte.
  const std::string name_c("\x01\x00\x01\x00" "C", 5);
  const std::size_t at = bytes.find(name_c);
  if (at == std::string::npos) std::abort();
  bytes[at + 4] = 'A';
  return bytes;
}

// plant.mat with an n x n state matrix -I (compressed: a few KB).
std::string PlantMatStates(std::size_t n) {
  const fs::path dir = TempDir("catalogue_matn"), tmp = dir / "plant.mat";
  mat_t* mat = Mat_CreateVer(tmp.c_str(), nullptr, MAT_FT_MAT5);
  if (mat == nullptr) std::abort();
  auto put = [&](const char* name, std::vector<double> v, std::size_t rows, std::size_t cols) {
    std::size_t dims[2] = {rows, cols};
    matvar_t* var = Mat_VarCreate(name, MAT_C_DOUBLE, MAT_T_DOUBLE, 2, dims, v.data(), 0);
    if (var == nullptr || Mat_VarWrite(mat, var, MAT_COMPRESSION_ZLIB) != 0) std::abort();
    Mat_VarFree(var);
  };
  std::vector<double> a(n * n, 0.0);
  for (std::size_t i = 0; i < n; ++i) a[i * n + i] = -1.0;
  put("A", a, n, n);
  put("B", std::vector<double>(n, 1.0), n, 1);
  put("C", std::vector<double>(n, 1.0), 1, n);
  if (Mat_Close(mat) != 0) std::abort();
  std::string bytes = ReadAll(tmp);
  fs::remove_all(dir);
  return bytes;
}

// A denominator of order `n`: s^n + 1.
std::string DenOfOrder(std::size_t n) {
  std::string s = "den: [1";
  for (std::size_t i = 0; i < n; ++i) s += i + 1 == n ? ", 1" : ", 0";
  return s + "]";
}


// A sweep section over the base budget.
std::string Sweep(const std::string& section) { return kBase + "sweep:\n" + section; }
const std::string kSweep = Sweep("  parameters:\n    - {path: \"sources[0].spectrum.level\", values: [1.0e-6, 2.0e-6]}\n");
std::string SweepPath(const std::string& path) {
  return Sweep("  parameters:\n    - {path: \"" + path + "\", values: [1.0e-6, 2.0e-6]}\n");
}

// The base plant made unstable, its exact variance required: an error only
// the engine finds (PlanEvaluation), at contributors[0].path.
const std::string kUnstableRequired =
    Sub(Sub(kBase, "den: [1, 2, 100]", "den: [1, -2, 100]"), "path: plant}", "path: plant, exact: required}");

// Nested aliases: 9 levels of 10, 10^9 leaves if anything expanded them.
std::string AliasBomb(const std::string& leaf) {
  std::string s = "[&l0 [" + leaf;
  for (int i = 1; i < 10; ++i) s += ", " + leaf;
  s += "]";
  for (int level = 1; level < 9; ++level) {
    s += ", &l" + std::to_string(level) + " [*l" + std::to_string(level - 1);
    for (int i = 1; i < 10; ++i) s += ", *l" + std::to_string(level - 1);
    s += "]";
  }
  return s + "]";
}

// A two-channel source with a correlation, through a 1 x 2 gain.
std::string Correlated(const std::string& correlation) {
  return Sub(Sub(kBase, "    unit: N\n", "    unit: N\n    channels: 2\n    correlation: " + correlation + "\n"),
             kTf + "    inputs: [u]\n", "type: gain\n    gain: [[1, 1]]\n");
}

// The base output with a measured reference in `unit` read from ref.csv.
std::string Reference(const std::string& unit) {
  return Sub(kBase, "rms_max: 5}",
             "rms_max: 5, references: [{name: r, unit: " + unit + ", spectrum: {type: measured, file: ref.csv}}]}");
}

// A feedback loop around the plant with a gain controller.
std::string Loop(const std::string& controller_units, const std::string& loop_tail) {
  return Sub(kBase, "contributors:\n",
             "  - {name: k, type: gain, gain: [[1000]], " + controller_units + "}\n"
             "  - {name: fb, type: feedback, plant: plant, controller: k" + loop_tail + "}\ncontributors:\n");
}

// Injection payloads run `touch $DEBINJ`: DEBINJ (set for every case) is the
// absolute path of INJECTED in the case directory, wherever gnuplot runs.
// The name has no '_', which gnuplot's enhanced-text escaping would alter.
// The budget's descriptions and channel names carry a backquoted command.
const std::string kInjectionBudget = Sub(
    Sub(Sub(Sub(Sub(Sub(kBase, "description: bad-input catalogue base budget",
                        "description: \"x`touch $DEBINJ`\""),
                    "    unit: N\n", "    unit: N\n    description: \"s`touch $DEBINJ`\"\n"),
                "    type: transfer_function\n", "    description: \"p`touch $DEBINJ`\"\n    type: transfer_function\n"),
            "{name: c1, source: noise, path: plant}", "{name: c1, source: noise, path: plant, description: \"c`touch $DEBINJ`\"}"),
        "rms_max: 5}", "rms_max: 5, description: \"o`touch $DEBINJ`\", weighting: {num: [1], den: [0.001, 1], unit: s, description: \"w`touch $DEBINJ`\"}}"),
    "inputs: [u]", "inputs: [\"u`touch $DEBINJ`\"]");
const std::string kInjectionChannels =
    Sub(Sub(kBase, "    unit: N\n", "    unit: N\n    channels: [\"a`touch $DEBINJ`\"]\n"), "inputs: [u]",
        "inputs: [\"a`touch $DEBINJ`\"]");

// A summary.json as deb compare reads it, with one part replaced.
std::string Summary(const std::string& contributors, const std::string& bands, const std::string& variance = "1e-3") {
  return "{\"budget\": \"r\", \"outputs\": [{\"name\": \"z\", \"unit\": \"nm\", \"rms\": 0.03, \"variance\": " +
         variance + ", \"requirement\": null, \"contributors\": " + contributors + ", \"bands\": " + bands + "}]}\n";
}
const std::string kGoodContributors = "[{\"name\": \"c1\", \"variance\": 1e-3}]";

// A deb report written earlier into `dir` from a budget 4x the base level.
std::string EarlierReport(const std::string& dir) {
  return "\"$DEB\" run old.yaml -q --no-plots --out " + dir + " && cp " + dir + "/summary.json ../io/old_summary.json";
}
const std::string kOld = Sub(kBase, "level: 1.0e-6", "level: 4.0e-6");

std::string CheckInjection(const fs::path& work, const Result& r);
std::string CheckNoPasswdLine(const fs::path& work, const Result& r);
std::string CheckDefaultReport(const fs::path& work, const Result& r);
std::string CheckSymlinkWrittenThrough(const fs::path& work, const Result& r);
std::string CheckPrevReplaced(const fs::path& work, const Result& r);
std::string CheckMydataReplaced(const fs::path& work, const Result& r);
std::string CheckBomRowKept(const fs::path& work, const Result& r);
std::string CheckCrRowsRead(const fs::path& work, const Result& r);

const std::string kRun = "run b.yaml --no-plots";
// "not a regular file" or "deb reads regular files only": either way the message says why.
const std::string kNotRegular = "regular file";
const std::string kHang = "#!/bin/sh\nsleep 30\n";
const Files kMydata = {{"b.yaml", kBase}, {"mydata/thesis.tex", "\\documentclass{article}\n"},
                       {"mydata/main.c", "int main(void) { return 0; }\n"}};

// ---------------------------------------------------------------------------
// The catalogue.

// The base budget with parameters k (5 N/m) and m (2 kg) and the source's
// level written as `level` (block style: an expression may hold ", {}").
Files Expr(const std::string& level, const std::string& parameters = "  k: 5 N/m\n  m: 2 kg\n") {
  return Budget(Sub(Sub(kBase, "description: bad-input catalogue base budget\n",
                        "description: bad-input catalogue base budget\nparameters:\n" + parameters),
                    "    spectrum: {type: flat, level: 1.0e-6}\n",
                    "    spectrum:\n      type: flat\n      level: " + level + "\n"));
}

// ---- Y: YAML budgets -------------------------------------------------------
[[gnu::noinline]] std::vector<Case> YamlBudgetCases() {
  return {
      {"Y00", "valid baseline budget", B(), kRun, 0, Ok(), {}, {}, "", "", 0, CheckDefaultReport},
      {"Y00p", "valid baseline budget, with plots", B(), "run b.yaml", 0, Ok(), {}, {}, "", "", 0, CheckDefaultReport},
      {"Y00c", "deb check of the baseline", B(), "check b.yaml", 0, Ok()},
      {"Y01", "syntax: unclosed flow sequence", B("den: [1, 2, 100]", "den: [1, 2, 100"), kRun, 3, At("", "")},
      {"Y02", "syntax: tab indentation", B("    unit: N\n", "\tunit: N\n"), kRun, 3, At("", "")},
      {"Y03", "empty file", Budget(""), kRun, 3, InFile("b.yaml")},
      {"Y04", "root is a list", Budget("- a\n- b\n"), kRun, 3, InFile("b.yaml")},
      {"Y05", "root is a scalar", Budget("just words\n"), kRun, 3, InFile("b.yaml")},
      {"Y06", "missing required key name", B("name: cat\n", ""), kRun, 3, At("", ""), {"'name'"}},
      {"Y07", "missing required key sources", B(kSourceBlock, ""), kRun, 3, At("", ""), {"'sources'"}},
      {"Y08", "unknown root key", B("paths:\n", "colour: red\npaths:\n"), kRun, 3, At("colour", "colour")},
      {"Y09", "unknown key in a source", B("    unit: N\n", "    unit: N\n    levle: 3\n"), kRun, 3,
       At("levle", "sources[0].levle")},
      {"Y10", "level is a word", B("level: 1.0e-6", "level: abc"), kRun, 3, At("abc", "sources[0].spectrum.level")},
      {"Y11", "level .nan", B("level: 1.0e-6", "level: .nan"), kRun, 3, At(".nan", "sources[0].spectrum.level")},
      {"Y12", "level .inf", B("level: 1.0e-6", "level: .inf"), kRun, 3, At(".inf", "sources[0].spectrum.level")},
      {"Y13", "level negative", B("level: 1.0e-6", "level: -1"), kRun, 3, At("level: |-1", "sources[0].spectrum.level")},
      {"Y14", "level 1e400", B("level: 1.0e-6", "level: 1e400"), kRun, 3, At("1e400", "sources[0].spectrum.level")},
      {"Y15", "level is a list", B("level: 1.0e-6", "level: [1, 2]"), kRun, 3,
       At("level: |[1, 2]", "sources[0].spectrum.level")},
      {"Y16", "rms_max 0", B("rms_max: 5", "rms_max: 0"), kRun, 3, At("rms_max: |0", "outputs[0].rms_max")},
      {"Y17", "rms_max negative", B("rms_max: 5", "rms_max: -5"), kRun, 3, At("rms_max: |-5", "outputs[0].rms_max")},
      {"Y18", "sources: []", B(kSourceBlock, "sources: []\n"), kRun, 3, At("source: |noise", "contributors[0].source")},
      {"Y19", "contributors: []", B("contributors:\n  - {name: c1, source: noise, path: plant}\n", "contributors: []\n"),
       kRun, 3, At("contributors: |[]", "contributors")},
      {"Y20", "outputs: []", B("outputs:\n  - {name: z, signal: y, unit: nm, rms_max: 5}\n", "outputs: []\n"), kRun, 3,
       At("outputs: |[]", "outputs")},
      {"Y21", "duplicate source names", B("paths:\n", "  - {name: noise, unit: N, spectrum: {type: flat, level: 1}}\npaths:\n"),
       kRun, 3, At("{name: |noise, unit", "sources[1].name")},
      {"Y22", "duplicate path names",
       B("contributors:\n", "  - {name: plant, type: gain, gain: [[1]], input_unit: N, output_unit: um}\ncontributors:\n"),
       kRun, 3, At("{name: |plant, type: gain", "paths[1].name")},
      {"Y23", "duplicate contributor names", B("outputs:\n", "  - {name: c1, path: plant, source: noise}\noutputs:\n"), kRun,
       3, At("{name: |c1, path", "contributors[1].name")},
      {"Y24", "duplicate output names", Budget(kBase + "  - {name: z, unit: nm, signal: y}\n"), kRun, 3,
       At("{name: |z, unit", "outputs[1].name")},
      {"Y25", "duplicate YAML key (D10): located at the second key", B("level: 1.0e-6}", "level: 1.0e-6, level: 5}"),
       kRun, 3, At("level: 5", "sources[0].spectrum.level")},
      {"Y25+", "duplicate YAML key at the root (D10)", Budget(kBase + "name: other\n"), kRun, 3, At("name: other", "name")},
      {"Y26", "dangling contributor source", B("source: noise", "source: nosuch"), kRun, 3,
       At("nosuch", "contributors[0].source")},
      {"Y27", "dangling contributor path", B("path: plant}", "path: nosuch}"), kRun, 3, At("nosuch", "contributors[0].path")},
      {"Y28", "dangling output signal", B("signal: y", "signal: q"), kRun, 3, At("signal: |q", "outputs[0].signal")},
      {"Y29", "series referring to itself", B("contributors:\n", "  - {name: loop, type: series, of: [plant, loop]}\ncontributors:\n"),
       kRun, 3, At("plant, |loop]", "paths[1].of[1]")},
      {"Y30", "series cycle a -> b -> a",
       B("contributors:\n",
         "  - {name: a, type: series, of: [plant, b]}\n  - {name: b, type: series, of: [plant, a]}\ncontributors:\n"),
       kRun, 3, At("plant, |b]", "paths[1].of[1]")},
      {"Y31", "feedback around itself",
       B("contributors:\n", "  - {name: fb, type: feedback, plant: fb, controller: plant}\ncontributors:\n"), kRun, 3,
       At("plant: |fb", "paths[1].plant")},
      {"Y32", "series of one path", B("contributors:\n", "  - {name: s, type: series, of: [plant]}\ncontributors:\n"), kRun,
       3, At("of: |[plant]", "paths[1].of")},
      {"Y33", "unstable path, exact: required",
       B("den: [1, 2, 100]", "den: [1, -2, 100]", "path: plant}", "path: plant, exact: required}"), kRun, 3,
       At("path: |plant, exact", "contributors[0].path")},
      {"Y34", "unstable path, exact: auto", B("den: [1, 2, 100]", "den: [1, -2, 100]"), kRun, 3,
       At("path: |plant}", "contributors[0].path")},
      {"Y35", "undamped pole exactly on an explicit grid point",
       B("{type: log, min_hz: 1, max_hz: 100, points: 50}", "{type: explicit, f_hz: [1, 10, 100]}", "den: [1, 2, 100]",
         "den: [1, 0, 3947.8417604357433]"),
       kRun, 3, At("{name: c1", "contributors[0]")},
      {"Y36", "channel count mismatch", B("    unit: N\n", "    unit: N\n    channels: 3\n"), kRun, 3,
       At("{name: c1", "contributors[0]")},
      {"Y37", "source N into a path input in m", B("input_unit: N", "input_unit: m"), kRun, 3,
       At("{name: c1", "contributors[0]")},
      {"Y38", "output unit kg from um", B("unit: nm", "unit: kg"), kRun, 3, At("unit: |kg", "outputs[0].unit")},
      {"Y39", "nonsense unit string", B("unit: N\n", "unit: furlongs/fortnight^^\n"), kRun, 3,
       At("furlongs", "sources[0].unit")},
      {"Y40", "grid points 1e12", B("points: 50", "points: 1e12"), kRun, 3, At("1e12", "grid.points")},
      {"Y41", "grid points 2000000000 (16 GB)", B("points: 50", "points: 2000000000"), kRun, 3, At("", "grid"), {}, {}, "",
       "", 30},
      {"Y42", "grid points 1 (D07)", B("points: 50", "points: 1"), kRun, 3, At("", "grid")},
      {"Y43", "grid points -5 (D07)", B("points: 50", "points: -5"), kRun, 3, At("", "grid")},
      {"Y44", "grid points 2.5", B("points: 50", "points: 2.5"), kRun, 3, At("2.5", "grid.points")},
      {"Y45", "log grid min_hz > max_hz (D07)", B("min_hz: 1, max_hz: 100", "min_hz: 100, max_hz: 1"), kRun, 3,
       At("", "grid")},
      {"Y46", "log grid min_hz == max_hz (D07)", B("min_hz: 1, max_hz: 100", "min_hz: 10, max_hz: 10"), kRun, 3,
       At("", "grid")},
      {"Y46+", "linear grid min_hz > max_hz (D07)",
       B("{type: log, min_hz: 1, max_hz: 100, points: 50}", "{type: linear, min_hz: 100, max_hz: 1, points: 50}"), kRun,
       3, At("", "grid")},
      {"Y46++", "linear grid min_hz == max_hz (D07)",
       B("{type: log, min_hz: 1, max_hz: 100, points: 50}", "{type: linear, min_hz: 10, max_hz: 10, points: 50}"), kRun,
       3, At("", "grid")},
      {"Y46+++", "linear grid points 1 (D07)",
       B("{type: log, min_hz: 1, max_hz: 100, points: 50}", "{type: linear, min_hz: 1, max_hz: 100, points: 1}"), kRun,
       3, At("", "grid")},
      {"Y47", "grid min_hz 0", B("min_hz: 1,", "min_hz: 0,"), kRun, 3, At("min_hz: |0", "grid.min_hz")},
      {"Y48", "explicit grid f_hz: []", B("{type: log, min_hz: 1, max_hz: 100, points: 50}", "{type: explicit, f_hz: []}"),
       kRun, 3, At("", "grid.f_hz")},
      {"Y49", "explicit grid not increasing",
       B("{type: log, min_hz: 1, max_hz: 100, points: 50}", "{type: explicit, f_hz: [1, 5, 5, 10]}"), kRun, 3,
       At("", "grid.f_hz")},
      {"Y50", "grid type bogus", B("type: log", "type: cubic"), kRun, 3, At("cubic", "grid.type")},
      {"Y51", "auto grid points_per_decade 2e9 (D06)",
       B("{type: log, min_hz: 1, max_hz: 100, points: 50}",
         "{type: auto, min_hz: 1, max_hz: 100, points_per_decade: 2000000000}"),
       kRun, 3, At("", "grid"), {}, {}, "", "", 30},
      {"Y52", "auto grid points_per_decade 0",
       B("{type: log, min_hz: 1, max_hz: 100, points: 50}", "{type: auto, min_hz: 1, max_hz: 100, points_per_decade: 0}"),
       kRun, 3, At("", "grid")},
      {"Y53", "auto grid 1e-300..1e300 Hz (D06)",
       B("{type: log, min_hz: 1, max_hz: 100, points: 50}", "{type: auto, min_hz: 1.0e-300, max_hz: 1.0e300}"), kRun, 3,
       At("", "grid"), {}, {}, "", "", 30},
      {"Y54", "log grid 1e-300..1e300 Hz (D22)", B("min_hz: 1, max_hz: 100", "min_hz: 1.0e-300, max_hz: 1.0e300"), kRun,
       3, At("", "grid"), {}, {}, "", "", 30},
      {"Y55", "band lo > hi", Budget(kBase + "bands:\n  - [10, 1]\n"), kRun, 3, At("  - |[10, 1]", "bands[0]")},
      {"Y56", "band with one number", Budget(kBase + "bands:\n  - [1]\n"), kRun, 3, At("  - |[1]", "bands[0]")},
      {"Y57", "band_requirements lo == hi",
       B("rms_max: 5}", "rms_max: 5, band_requirements: [{lo_hz: 5, hi_hz: 5, rms_max: 1}]}"), kRun, 3,
       At("[|{lo_hz: 5", "outputs[0].band_requirements[0]")},
      {"Y58", "den: []", B("den: [1, 2, 100]", "den: []"), kRun, 3, At("- |name: plant", "paths[0]")},
      {"Y59", "den all zeros", B("den: [1, 2, 100]", "den: [0, 0, 0]"), kRun, 3, At("- |name: plant", "paths[0]")},
      {"Y60", "improper transfer function", B("num: [1]", "num: [1, 0, 0, 0]"), kRun, 3, At("- |name: plant", "paths[0]")},
      {"Y61", "state-space dimension mismatch",
       B(kTf, "type: state_space\n    A: [[0, 1], [-100, -2]]\n    B: [[0], [1], [2]]\n    C: [[1, 0]]\n    D: [[0]]\n"),
       kRun, 3, At("- |name: plant", "paths[0]")},
      {"Y62", "state-space A not square",
       B(kTf, "type: state_space\n    A: [[0, 1, 0], [-100, -2, 0]]\n    B: [[0], [1]]\n    C: [[1, 0]]\n    D: [[0]]\n"),
       kRun, 3, At("- |name: plant", "paths[0]")},
      {"Y63", "ragged matrix",
       B(kTf, "type: state_space\n    A: [[0, 1], [-100]]\n    B: [[0], [1]]\n    C: [[1, 0]]\n    D: [[0]]\n"), kRun,
       3, At("[[0, 1], |[-100]]", "paths[0].A[1]")},
      // N05 of the reliability audit: finite but extreme coefficients ended
      // in an abort of the Schur form (exit 134), or in "frequency 1 Hz
      // coincides with a pole at -1e+300 rad/s".
      {"Y63+", "state-space A with an entry -1e300 (deb check)",
       B(kTf, "type: state_space\n    A: [[0, 1], [-1e300, -2]]\n    B: [[0], [1]]\n    C: [[1, 0]]\n    D: [[0]]\n"),
       "check b.yaml", 3, At("path: |plant}", "contributors[0].path"), {"too badly scaled"}, {"internal error"}},
      {"Y63++", "state-space A with an entry -1e300 (run)",
       B(kTf, "type: state_space\n    A: [[0, 1], [-1e300, -2]]\n    B: [[0], [1]]\n    C: [[1, 0]]\n    D: [[0]]\n"),
       kRun, 3, At("path: |plant}", "contributors[0].path"), {"too badly scaled"}, {"internal error"}},
      {"Y63+++", "transfer function with coefficients 1e300",
       B("num: [1]\n    den: [1, 2, 100]", "num: [1e300, 1]\n    den: [1, 2, 1e300]"), kRun, 3,
       At("path: |plant}", "contributors[0].path"), {"too badly scaled"}, {"internal error", "coincides with a pole"}},
      {"Y63++++", "transfer function with a pole at -1e300 rad/s",
       B("den: [1, 2, 100]", "den: [1, 1e300, 1]"), kRun, 3,
       At("path: |plant}", "contributors[0].path"), {"too badly scaled"}, {"internal error", "coincides with a pole"}},
      {"Y64", "gain: []", B(kTf + "    inputs: [u]\n    outputs: [y]\n", "type: gain\n    gain: []\n"), kRun, 3, At("{name: c1", "contributors[0]")},
      {"Y65", "correlation 1.5", Budget(Correlated("1.5")), kRun, 3, At("correlation: |1.5", "sources[0].correlation")},
      {"Y65+", "valid correlated two-channel source (baseline)", Budget(Correlated("0.3")), kRun, 0, Ok()},
      {"Y66", "correlation .nan", Budget(Correlated(".nan")), kRun, 3, At("correlation: |.nan", "sources[0].correlation")},
      {"Y67", "channels: 0", B("    unit: N\n", "    unit: N\n    channels: 0\n"), kRun, 3,
       At("channels: |0", "sources[0].channels")},
      {"Y68", "channels: 2000000000", B("    unit: N\n", "    unit: N\n    channels: 2000000000\n"), kRun, 3,
       At("channels: |2000000000", "sources[0].channels"), {}, {}, "", "", 30},
      {"Y69", "vc class bogus", B("{type: flat, level: 1.0e-6}", "{type: vc, class: VC-Z}"), kRun, 3,
       At("VC-Z", "sources[0].spectrum.class")},
      {"Y69b", "vc with both class and velocity", B("{type: flat, level: 1.0e-6}", "{type: vc, class: VC-C, velocity: 12.5}"),
       kRun, 3, At("{type: vc", "sources[0].spectrum"), {"both 'class' and 'velocity'"}},
      {"Y70", "vc lowest_band_hz > highest_band_hz",
       Budget(Sub(Sub(Sub(kBase, "{type: flat, level: 1.0e-6}", "{type: vc, class: VC-D, lowest_band_hz: 80, highest_band_hz: 2}"),
                      "    unit: N\n", "    unit: um/s\n"), "input_unit: N", "input_unit: um/s")), kRun, 3,
       At("spectrum: |{type: vc", "sources[0].spectrum")},
      {"Y71", "exact: bogus", B("path: plant}", "path: plant, exact: maybe}"), kRun, 3,
       At("maybe", "contributors[0].exact")},
      {"Y72", "budget name ../../escape", B("name: cat", "name: ../../escape"), kRun, 3, At("../../escape", "name")},
      {"Y73", "budget name '..' (D09)", B("name: cat", "name: '..'"), kRun, 3, At("name: |'..'", "name"), {}, {"Success"}},
      {"Y74", "budget name '.' (D09)", B("name: cat", "name: '.'"), kRun, 3, At("name: |'.'", "name"), {}, {"Success"}},
      {"Y75", "budget name empty", B("name: cat", "name: ''"), kRun, 3, At("name: |''", "name")},
      {"Y77", "non-scalar mapping key at the root (D05a)", Budget(kBase + "? [a, b] : 1\n"), kRun, 3, At("", "")},
      {"Y77b", "the 4-byte budget '? {}' (D05a, fuzzer)", Budget("? {}"), kRun, 3, At("", "")},
      {"Y77c", "'? {}' through deb check (D05a)", Budget("? {}"), "check b.yaml", 3, At("", "")},
      {"Y78", "non-scalar mapping key in a source (D05a)", B("    unit: N\n", "    unit: N\n    ? {k: v} : 1\n"), kRun, 3,
       At("", "sources[0]")},
      {"Y79", "weighting not SISO", B("rms_max: 5}", "rms_max: 5, weighting: {num: [[1, 2]], den: [1, 1], unit: s}}"),
       kRun, 3, At("num: [|[1, 2]]", "outputs[0].weighting.num[0]")},
      {"Y80", "metric window_s 0", B("rms_max: 5}", "rms_max: 5, metric: {type: moving_std, window_s: 0}}"), kRun, 3,
       At("window_s: |0", "outputs[0].metric.window_s")},
      {"Y81", "metric window_s 1e300 (valid)", B("rms_max: 5}", "metric: {type: moving_std, window_s: 1.0e300}}"), kRun, 0,
       Ok()},
      {"Y82", "metric window_s 1e-300 (valid)", B("rms_max: 5}", "metric: {type: moving_average, window_s: 1.0e-300}}"),
       kRun, 0, Ok()},
      {"Y83", "YAML hex number 0x64 (valid)", B("den: [1, 2, 100]", "den: [1, 2, 0x64]"), kRun, 0, Ok()},
      {"Y84", "NUL byte in the budget name", B("name: cat", std::string("name: \"c\0at\"", 12)), kRun, 3, At("", "name")},
      {"Y85", "invalid UTF-8 in the budget name", B("name: cat", "name: \"c\xff\xfe" "at\""), kRun, 3, At("", "name")},
      {"Y86", "reference model bogus", B("{type: flat, level: 1.0e-6}", "{type: reference, model: xlnm}"), kRun, 3,
       At("xlnm", "sources[0].spectrum.model")},
      {"Y89", "sign: 0 in feedback", Budget(Loop("input_unit: um, output_unit: N", ", sign: 0")), kRun, 3,
       At("sign: |0", "paths[2].sign")},
      {"Y90", "unstable closed loop, exact: required",
       Budget(Sub(Loop("input_unit: um, output_unit: N", ", sign: 1"), "path: plant}", "path: fb, exact: required}")),
       kRun, 3, At("path: |fb", "contributors[0].path")},
      {"Y91", "feedback controller unit mismatch", Budget(Loop("input_unit: kg, output_unit: N", "")), kRun, 3,
       At("controller: |k", "paths[2].controller")},
      {"Y92", "flat lo_hz > hi_hz", B("{type: flat, level: 1.0e-6}", "{type: flat, level: 1.0e-6, lo_hz: 50, hi_hz: 5}"),
       kRun, 3, At("spectrum: |{type: flat", "sources[0].spectrum")},
      {"Y93", "convention bogus", B("    unit: N\n", "    unit: N\n    convention: three-sided\n"), kRun, 3,
       At("three-sided", "sources[0].convention")},
      {"Y94", "correlation matrix with -1 on the diagonal", Budget(Correlated("[[1, 0.5], [0.5, -1]]")), kRun, 3,
       At("correlation: |[[1", "sources[0].correlation")},
      {"Y95", "auto grid points_per_resonance 2e9",
       B("{type: log, min_hz: 1, max_hz: 100, points: 50}",
         "{type: auto, min_hz: 1, max_hz: 100, points_per_resonance: 2000000000}", "den: [1, 2, 100]",
         "den: [1, 0.2, 100]"),
       kRun, 3, At("", "grid"), {}, {}, "", "", 30},
      {"Y97", "exact: required with a band-limited (not white) source",
       B("{type: flat, level: 1.0e-6}", "{type: flat, level: 1.0e-6, lo_hz: 2, hi_hz: 50}", "path: plant}",
         "path: plant, exact: required}"),
       kRun, 3, At("exact: |required", "contributors[0].exact")},
      {"Y98", "log grid points 100000000 (800 MB per array)", B("points: 50", "points: 100000000"), kRun, 3,
       At("", "grid"), {}, {}, "", "", 30},
      {"Y98+", "deb check with log grid points 2000000000", B("points: 50", "points: 2000000000"), "check b.yaml", 3,
       At("", "grid"), {}, {}, "", "", 30},
  };
}

// ---- P: parameters and expressions -----------------------------------------
[[gnu::noinline]] std::vector<Case> ParameterCases() {
  return {
      {"P00", "valid: a level from parameters", Expr("2*k/(1 N/m)*1e-7"), kRun, 0, Ok()},
      {"P01", "expression ends after an operator", Expr("1 +"), kRun, 3, At("level: 1 +|", "sources[0].spectrum.level"),
       {"expected a number, a name or '(' but the expression ends"}},
      {"P02", "'(' not closed", Expr("(1 + 2"), kRun, 3, At("level: |(1 + 2", "sources[0].spectrum.level"), {"not closed"}},
      {"P03", "')' without '('", Expr("1 + 2)"), kRun, 3, At("1 + 2|)", "sources[0].spectrum.level")},
      {"P04", "two operators", Expr("2 * * 3"), kRun, 3, At("2 * |* 3", "sources[0].spectrum.level"), {"unexpected '*'"}},
      {"P05", "unknown name", Expr("abc + 1"), kRun, 3, At("level: |abc + 1", "sources[0].spectrum.level"),
       {"unknown name 'abc'"}},
      {"P06", "misspelt parameter", Expr("kk*2"), kRun, 3, At("level: |kk*2", "sources[0].spectrum.level"),
       {"did you mean 'k'?"}},
      {"P07", "adding N/m and kg", Expr("k + m"), kRun, 3, At("k |+ m", "sources[0].spectrum.level"),
       {"cannot add kg s-2 and kg"}},
      {"P08", "division by zero", Expr("1/0"), kRun, 3, At("1|/0", "sources[0].spectrum.level"), {"division by zero"}},
      {"P09", "sqrt of a negative number", Expr("sqrt(-1)"), kRun, 3, At("level: |sqrt(-1)", "sources[0].spectrum.level")},
      {"P10", "log of zero", Expr("log(0)"), kRun, 3, At("level: |log(0)", "sources[0].spectrum.level"),
       {"not positive"}},
      {"P11", "exp overflows", Expr("exp(1000)"), kRun, 3, At("level: |exp(1000)", "sources[0].spectrum.level"),
       {"not finite"}, {"inf", "nan"}},
      {"P12", "product overflows", Expr("1e300*1e300"), kRun, 3, At("1e300|*1e300", "sources[0].spectrum.level"),
       {"not finite"}},
      {"P13", "a number beyond double", Expr("1e400 + 1"), kRun, 3, At("level: |1e400 + 1", "sources[0].spectrum.level"),
       {"beyond"}},
      {"P14", "unknown function", Expr("foo(2)"), kRun, 3, At("level: |foo(2)", "sources[0].spectrum.level"),
       {"unknown function 'foo'"}},
      {"P15", "unknown unit", Expr("2 zorks"), kRun, 3, At("2 |zorks", "sources[0].spectrum.level"), {"unknown unit 'zorks'"}},
      {"P16", "exp of a length", Expr("exp(1 m)"), kRun, 3, At("level: |exp(1 m)", "sources[0].spectrum.level"),
       {"dimensionless"}},
      {"P17", "a length to the power 0.3", Expr("(1 m)^0.3"), kRun, 3, At("(1 m)|^0.3", "sources[0].spectrum.level"),
       {"multiples of 1/2"}},
      {"P18", "a quantity where a plain number goes", Expr("k"), kRun, 3, At("level: |k", "sources[0].spectrum.level"),
       {"'k' is a quantity in kg s-2; this value is a plain number"}},
      {"P19", "nested 100 deep", Expr(std::string(100, '(') + "1" + std::string(100, ')')), kRun, 3,
       At("", "sources[0].spectrum.level"), {"nested deeper than 64 levels"}},
      {"P20", "a 1 MB expression", Expr([] {
         std::string sum = "1";
         while (sum.size() < (1u << 20)) sum += "+1";
         return sum;
       }()), kRun, 3,
       At("", "sources[0].spectrum.level"), {"longer than 4096 bytes"}},
      {"P21", "parameters in a cycle", Expr("a", "  a: b + 1\n  b: 2*a\n"), kRun, 3, At("a: |b + 1", "parameters.a"),
       {"cycle: a -> b -> a"}},
      {"P22", "a parameter uses an unknown name", Expr("1", "  k: 5 N/m\n  f: sqrt(k/mass)\n"), kRun, 3,
       At("sqrt(k/|mass)", "parameters.f"), {"unknown name 'mass'"}},
      {"P23", "a parameter named pi", Expr("1", "  pi: 3\n"), kRun, 3, At("pi: |3", "parameters.pi"),
       {"'pi' is not a parameter name"}},
      {"P24", "a parameter that is a list", Expr("1", "  k: [1, 2]\n"), kRun, 3, At("k: |[1, 2]", "parameters.k"),
       {"a parameter's value is a number with its unit or an expression"}},
      {"P25", "a length for max_hz", B("max_hz: 100", "max_hz: 2 m"), kRun, 3, At("max_hz: |2 m", "grid.max_hz"),
       {"'2 m' is a quantity in m; this value is in Hz"}},
      {"P26", "rad/s for a frequency", B("max_hz: 100", "max_hz: 600 rad/s"), kRun, 3,
       At("max_hz: |600 rad/s", "grid.max_hz"), {"give frequencies in Hz, not rad/s"}},
      {"P27", "--set of a parameter to a division by zero", Expr("k/(1 N/m)*1e-7"), "run b.yaml --no-plots --set k=1/0",
       3, At("", "parameters.k"), {"division by zero"}},
      {"P28", "a 10000-long chain of parameters", Expr("p0", [] {
         std::string chain;
         for (int i = 0; i < 10000; ++i) chain += "  p" + std::to_string(i) + ": p" + std::to_string(i + 1) + " + 1\n";
         return chain + "  p10000: 1\n";
       }()), kRun, 3, At("", "parameters"), {"more than 10000 parameters"}},
  };
}

// ---- D: delays and sampled blocks ------------------------------------------
[[gnu::noinline]] std::vector<Case> DelayAndSampledCases() {
  return {
      {"D00", "valid: a delay as the path", B(kTf, "type: delay\n    seconds: 1 ms\n"), kRun, 0, Ok()},
      {"D01", "a negative delay", B(kTf, "type: delay\n    seconds: -1 ms\n"), kRun, 3,
       At("seconds: |-1 ms", "paths[0].seconds"), {"finite number of seconds >= 0"}},
      {"D02", "a delay in metres", B(kTf, "type: delay\n    seconds: 2 m\n"), kRun, 3,
       At("seconds: |2 m", "paths[0].seconds"), {"'2 m' is a quantity in m"}},
      {"D03", "a Pade order of 0", B(kTf, "type: delay\n    seconds: 1 ms\n    pade_order: 0\n"), kRun, 3,
       At("pade_order: |0", "paths[0].pade_order"), {"pade_order must be 1 to 12, not 0"}},
      {"D04", "a sampled block that is not causal",
       B(kTf, "type: discrete\n    sample_hz: 1000\n    num: [1, 0, 0]\n    den: [1, -0.5]\n"), kRun, 3,
       At("den: |[1, -0.5]", "paths[0].den"), {"not causal", "degree 2"}},
      {"D05", "a sampled block with a pole at z = -1",
       B(kTf, "type: discrete\n    sample_hz: 1000\n    num: [1]\n    den: [1, 1]\n"), kRun, 3,
       At("den: |[1, 1]", "paths[0].den"), {"root at z = -1"}},
      {"D06", "a sampling rate of 0", B(kTf, "type: discrete\n    sample_hz: 0\n    num: [1]\n    den: [1, -0.5]\n"),
       kRun, 3, At("sample_hz: |0", "paths[0].sample_hz"), {"sample_hz must be > 0"}},
      {"D07", "a hold that is not true or false",
       B(kTf, "type: discrete\n    sample_hz: 1000\n    num: [1]\n    den: [1, -0.5]\n    zoh: maybe\n"), kRun, 3,
       At("zoh: |maybe", "paths[0].zoh")},
      {"D08", "an unstable sampled block", B(kTf, "type: discrete\n    sample_hz: 1000\n    num: [1]\n    den: [1, -2]\n"),
       kRun, 3, At("", "contributors[0].path"), {"unstable"}},
      {"D09", "a sampled block's conjugate pair in z with im 0",
       B(kTf, "type: discrete\n    sample_hz: 1000\n    poles: [{re: 0.5, im: 0}]\n"), kRun, 3,
       At("poles: [{re: 0.5, im: |0}]", "paths[0].poles[0].im"), {"a conjugate pair needs im != 0"}},
      {"L00", "valid: one mass on a spring as the path", B(kPlant, kMass), kRun, 0, Ok()},
      {"L01", "a coupling to a mass that does not exist", B(kPlant, Sub(kMass, "[m, ground]", "[n, ground]")), kRun, 3,
       At("between: [|n, ground]", "paths[0].couplings[0].between[0]"), {"no mass 'n' (the masses: m, ground)"}},
      {"L02", "a negative stiffness", B(kPlant, Sub(kMass, "k: 100 N/m", "k: -100 N/m")), kRun, 3,
       At("k: |-100 N/m", "paths[0].couplings[0].k"), {"must be >= 0"}},
      {"L03", "an input that is a force and the ground", B(kPlant, Sub(kMass, "force: m}", "force: m, ground: acceleration}")),
       kRun, 3, At("inputs: [|{name: u", "paths[0].inputs[0]"), {"give 'force: mass'"}},
      {"L04", "a displacement output in newtons", B(kPlant, kMass, "output_unit: um", "output_unit: N"), kRun, 3,
       At("output_unit: |N", "paths[0].output_unit"), {"output 'y' is in m: 'N' is not the same quantity"}},
      {"L05", "a mass in metres", B(kPlant, Sub(kMass, "{m: 1 kg}", "{m: 1 m}")), kRun, 3,
       At("masses: {m: |1 m}", "paths[0].masses.m"), {"'1 m' is a quantity in m"}},
      {"X10", "YAML nesting 100000 deep", Budget(kBase + "extra: " + std::string(100000, '[') + "\n"), kRun, 3, At("", "")},
      {"X11", "YAML nesting 1500 deep inside description",
       B("description: bad-input catalogue base budget", "description: " + std::string(1500, '[') + std::string(1500, ']')),
       kRun, 3, At("", "")},
      {"X12", "alias bomb as the description value", B("description: bad-input catalogue base budget", "description: " + AliasBomb("lol")),
       kRun, 3, At("", "description")},
      {"X13", "alias bomb as unknown root keys", Budget("a: " + AliasBomb("lol") + "\n" + kBase), kRun, 3, At("", "a")},
      {"X14", "alias bomb under an unknown key of sources[0]",
       B("    unit: N\n", "    unit: N\n    extra: " + AliasBomb("lol") + "\n"), kRun, 3, At("extra", "sources[0].extra")},
      {"X23", "output name ../../z", B("{name: z,", "{name: ../../z,"), kRun, 3, At("../../z", "outputs[0].name")},

      // "Did you mean": a misspelt key or name is answered with the nearest one.
      {"Y09+", "misspelt contributor key sorce", B("{name: c1, source: noise", "{name: c1, sorce: noise"), kRun, 3,
       At("sorce", "contributors[0].sorce"), {"unknown key 'sorce' (did you mean 'source'?); allowed here:"}},
      {"Y26+", "misspelt contributor source nois", B("source: noise", "source: nois"), kRun, 3,
       At("source: |nois", "contributors[0].source"), {"no source named 'nois' (did you mean 'noise'?)"}},
      {"Y27+", "misspelt contributor path plnt", B("path: plant}", "path: plnt}"), kRun, 3,
       At("path: |plnt", "contributors[0].path"), {"no path named 'plnt' (did you mean 'plant'?)"}},
      {"Y28+", "misspelt output signal yy", B("signal: y", "signal: yy"), kRun, 3, At("signal: |yy", "outputs[0].signal"),
       {"reads signal 'yy' (did you mean 'y'?)"}},
      {"Y29+", "series of a misspelt path",
       B("contributors:\n", "  - {name: s, type: series, of: [plant, plnt]}\ncontributors:\n"), kRun, 3,
       At("plant, |plnt]", "paths[1].of[1]"), {"no path named 'plnt' (did you mean 'plant'?)"}},
      {"Y38+", "a misspelt key far from every allowed one gets no suggestion", B("    unit: N\n", "    unit: N\n    zzz: 1\n"),
       kRun, 3, At("zzz", "sources[0].zzz"), {"unknown key 'zzz'; allowed here:"}, {"did you mean"}},
  };
}

// ---- W: sweeps -------------------------------------------------------------
[[gnu::noinline]] std::vector<Case> SweepCases() {
  return {
      {"W00", "valid sweep (baseline)", Budget(kSweep), "sweep b.yaml --no-plots", 0, Ok()},
      {"W00c", "deb check of a valid sweep", Budget(kSweep), "check b.yaml", 0, Ok()},
      {"W01", "sweep key path index overflows long (D05b)", Budget(SweepPath("paths[99999999999999999999].den[0]")),
       "sweep b.yaml --no-plots", 3, At("", "sweep.parameters[0]"), {"99999999999999999999"}},
      {"W01c", "the same through deb check (D05b)", Budget(SweepPath("paths[99999999999999999999].den[0]")), "check b.yaml",
       3, At("", "sweep.parameters[0]")},
      {"W02", "sweep key path not reaching a number", Budget(SweepPath("paths[0].name")), "sweep b.yaml --no-plots", 3,
       At("path: |\"paths[0].name\"", "sweep.parameters[0].path")},
      {"W03", "sweep key path missing key", Budget(SweepPath("paths[0].nosuch")), "sweep b.yaml --no-plots", 3,
       At("path: |\"paths[0].nosuch\"", "sweep.parameters[0].path")},
      {"W03+", "sweep key path with a misspelt key", Budget(SweepPath("sources[0].spectrum.levle")),
       "sweep b.yaml --no-plots", 3, At("path: |\"sources[0].spectrum.levle\"", "sweep.parameters[0].path"),
       {"has no key 'levle' (did you mean 'level'?)"}},
      {"W04", "sweep linear count 2e9 (D05d)",
       Budget(Sweep("  parameters:\n    - {path: \"sources[0].spectrum.level\", linear: {from: 1.0e-6, to: 2.0e-6, count: "
                    "2000000000}}\n")),
       "sweep b.yaml --no-plots", 3, At("", "sweep"), {}, {}, "", "", 30},
      {"W05", "sweep grid of 3 x 1000 values (1e9 variants, D05d)",
       Budget(Sweep("  parameters:\n"
                    "    - {path: \"sources[0].spectrum.level\", linear: {from: 1.0e-6, to: 2.0e-6, count: 1000}}\n"
                    "    - {path: \"paths[0].den[1]\", linear: {from: 1, to: 2, count: 1000}}\n"
                    "    - {path: \"paths[0].den[2]\", linear: {from: 100, to: 200, count: 1000}}\n")),
       "sweep b.yaml --no-plots", 3, At("", "sweep"), {}, {}, "", "", 30},
      {"W05c", "the 1e9-variant sweep through deb check (D05d)",
       Budget(Sweep("  parameters:\n"
                    "    - {path: \"sources[0].spectrum.level\", linear: {from: 1.0e-6, to: 2.0e-6, count: 1000}}\n"
                    "    - {path: \"paths[0].den[1]\", linear: {from: 1, to: 2, count: 1000}}\n"
                    "    - {path: \"paths[0].den[2]\", linear: {from: 100, to: 200, count: 1000}}\n")),
       "check b.yaml", 3, At("", "sweep"), {}, {}, "", "", 30},
      {"W06", "zip with unequal counts",
       Budget(Sweep("  mode: zip\n  parameters:\n"
                    "    - {path: \"sources[0].spectrum.level\", values: [1.0e-6, 2.0e-6, 3.0e-6]}\n"
                    "    - {path: \"paths[0].den[2]\", values: [100, 200]}\n")),
       "sweep b.yaml --no-plots", 3, At("- |{path: \"paths[0].den[2]\"", "sweep.parameters[1]")},
      {"W07", "a sweep value making a variant invalid",
       Budget(Sweep("  parameters:\n    - {path: \"sources[0].spectrum.level\", values: [1.0e-6, -1]}\n")),
       "sweep b.yaml --no-plots", 3, At("level: |1.0e-6", "sources[0].spectrum.level"), {"sweep variant 2"}},
      {"W07e", "an error only the engine finds, located in the budget (deb sweep)",
       Budget(kUnstableRequired + "sweep:\n  parameters:\n    - {path: \"sources[0].spectrum.level\", values: [1.0e-6]}\n"),
       "sweep b.yaml --no-plots", 3, At("path: |plant, exact", "contributors[0].path"), {"sweep variant 1", "unstable"}},
      {"W08", "no sweep section, deb sweep", B(), "sweep b.yaml --no-plots", 3, At("", ""), {"'sweep'"}},
      {"W09", "sweep key path through a map with a non-scalar key (D05a)",
       Budget(SweepPath("nosuch.x") + "? [a, b] : 1\n"), "sweep b.yaml --no-plots", 3, At("", "")},
      {"W10", "alias bomb in description, deb sweep",
       Budget(Sub(kSweep, "description: bad-input catalogue base budget", "description: " + AliasBomb("lol"))),
       "sweep b.yaml --no-plots", 3, At("", "description")},
      {"W11", "alias bomb in description, deb check with a sweep",
       Budget(Sub(kSweep, "description: bad-input catalogue base budget", "description: " + AliasBomb("lol"))),
       "check b.yaml", 3, At("", "description")},
      {"W12", "sweep [*] over an alias tree of 10^9 numbers (D13)",
       Budget(Sub(SweepPath("paths[0].num[*]"), "num: [1]", "num: " + AliasBomb("1"))), "sweep b.yaml --no-plots", 3,
       At("", ""), {}, {}, "", "", 30},
      {"W13", "sweep log range from 0",
       Budget(Sweep("  parameters:\n    - {path: \"sources[0].spectrum.level\", log: {from: 0, to: 1, count: 3}}\n")),
       "sweep b.yaml --no-plots", 3, At("log: |{from: 0", "sweep.parameters[0].log")},
      {"W14", "deb sweep --out onto an existing regular file (D02)", With(Budget(kSweep), "existing.txt", "keep me\n"),
       "sweep b.yaml --no-plots --out existing.txt", 4, Names("existing.txt"), {"not a report written by deb", "--force"}},
      {"W15", "deb sweep --out onto a directory of user files (D02)", With(kMydata, "b.yaml", kSweep),
       "sweep b.yaml --no-plots --out mydata", 4, Names("mydata"), {"--force"}},
      {"W16", "sweep label empty",
       Budget(Sweep("  parameters:\n    - {path: \"sources[0].spectrum.level\", label: \"\", values: [1.0e-6]}\n")),
       "sweep b.yaml --no-plots", 3, At("label: |\"\"", "sweep.parameters[0].label"), {"the label is empty"}},
      {"W17", "sweep unit unknown to UDUNITS-2",
       Budget(Sweep("  parameters:\n    - {path: \"sources[0].spectrum.level\", unit: umm, values: [1.0e-6]}\n")),
       "sweep b.yaml --no-plots", 3, At("unit: |umm", "sweep.parameters[0].unit"), {"umm"}},
  };
}

// ---- N: sensitivity --------------------------------------------------------
[[gnu::noinline]] std::vector<Case> SensitivityCases() {
  return {
      {"N00", "valid sensitivity (baseline)", B(), "sensitivity b.yaml -p 'sources[0].spectrum.level'", 0, Ok()},
      {"N01", "-p a key path that is not a number", B(), "sensitivity b.yaml -p 'paths[0].name'", 3,
       Names("paths[0].name")},
      {"N01+", "-p a key path with a misspelt key", B(), "sensitivity b.yaml -p 'sources[0].spectrum.levle'", 3,
       Names("sources[0].spectrum.levle"), {"has no key 'levle' (did you mean 'level'?)"}},
      {"N01e", "an error only the engine finds, located in the budget (deb sensitivity)", Budget(kUnstableRequired),
       "sensitivity b.yaml -p 'sources[0].spectrum.level'", 3, At("path: |plant, exact", "contributors[0].path"),
       {"unstable"}},
      {"N02", "--step 0", B(), "sensitivity b.yaml -p 'sources[0].spectrum.level' --step 0", 2, Usage()},
      {"N03", "--step 1", B(), "sensitivity b.yaml -p 'sources[0].spectrum.level' --step 1", 2, Usage()},
      {"N04", "--step nan (D19)", B(), "sensitivity b.yaml -p 'sources[0].spectrum.level' --step nan", 2, Usage()},
      {"N04+", "--step inf", B(), "sensitivity b.yaml -p 'sources[0].spectrum.level' --step inf", 2, Usage()},
      {"N05", "-p index overflowing long (D05b)", B(), "sensitivity b.yaml -p 'paths[99999999999999999999].den[0]'", 3,
       Names("paths[99999999999999999999]")},
      {"N06", "-p den[0] (valid)", B(), "sensitivity b.yaml -p 'paths[0].den[0]'", 0, Ok()},
      {"N07", "deb sensitivity --out onto an existing regular file (D02)", With(B(), "existing.txt", "keep me\n"),
       "sensitivity b.yaml -p 'sources[0].spectrum.level' --out existing.txt", 4, Names("existing.txt"),
       {"not a report written by deb", "--force"}},
  };
}

// ---- S: spectrum CSVs through a budget -------------------------------------
[[gnu::noinline]] std::vector<Case> SpectrumCsvBudgetCases() {
  return {
      {"S00", "valid spectrum CSV (baseline)", M(kSpec), kRun, 0, Ok()},
      {"S01", "empty spectrum file", M(""), kRun, 3, AtSpecFile(), {"0 data rows"}},
      {"S02", "header only", M("f_hz,z\n"), kRun, 3, AtSpecFile(), {"0 data rows"}},
      {"S03", "single data row", M("f_hz,z\n1,1e-6\n"), kRun, 3, AtSpecFile(), {"1 data rows"}},
      {"S04", "non-numeric cell", M(SpecSub("10,1e-6", "10,abc")), kRun, 3, AtSpecFile(), {"spec.csv:6:4:"}},
      {"S05", "non-increasing frequency", M(SpecSub("10,1e-6", "4,1e-6")), kRun, 3, AtSpecFile(), {"spec.csv:6:1:"}},
      {"S06", "negative frequency", M(SpecSub("0.5,1e-6", "-1,1e-6")), kRun, 3, AtSpecFile(), {"spec.csv:2:1:"}},
      {"S07", "NaN cell", M(SpecSub("10,1e-6", "10,nan")), kRun, 3, AtSpecFile(), {"spec.csv:6:4:"}},
      {"S08", "negative PSD", M(SpecSub("10,1e-6", "10,-1e-6")), kRun, 3, AtSpecFile(), {"spec.csv:6:4:"}},
      {"S09", "CRLF line endings (valid)", M(Sub(Sub(kSpec, "\n", "\r\n"), "0.5,1e-6\n", "0.5,1e-6\r\n")), kRun, 0, Ok()},
      {"S10", "UTF-8 BOM before the header (valid)", M(kBom + kSpec), kRun, 0, Ok()},
      {"S11", "UTF-8 BOM, no header, columns: [ch1] (D11)",
       M("{type: measured, file: spec.csv}", "{type: measured, file: spec.csv, columns: [ch1]}", kBom + kSpecRows), kRun,
       0, Ok()},
      {"S11n", "no BOM, no header, columns: [ch1] (valid)",
       M("{type: measured, file: spec.csv}", "{type: measured, file: spec.csv, columns: [ch1]}", kSpecRows), kRun, 0, Ok()},
      {"S11b", "UTF-8 BOM, no header, no column selection (D11)", M(kBom + kSpecRows), kRun, 0, Ok()},
      {"S12", "row with an extra cell", M(SpecSub("10,1e-6", "10,1e-6,3")), kRun, 3, AtSpecFile(), {"spec.csv:6:"}},
      {"S13", "cell 1e400", M(SpecSub("10,1e-6", "10,1e400")), kRun, 3, AtSpecFile(), {"spec.csv:6:4:"}},
      {"S14", "'# quantity: bogus'", M("# quantity: bogus\n" + kSpec), kRun, 3, AtSpecFile(), {"spec.csv:1:"}},
      {"S15", "'# unit:' an invalid unit", M("# unit: bananas^\n" + kSpec), kRun, 3, At("unit: |N", "sources[0].unit")},
      {"S16", "'# unit:' twice", M("# unit: N\n# unit: N\n" + kSpec), kRun, 3, AtSpecFile(), {"spec.csv:2:"}},
      {"S17", "one column only", M("f_hz\n1\n2\n"), kRun, 3, AtSpecFile(), {"spec.csv:1:1:"}},
      {"S18", "CR-only line endings (D23): read as lines", M(Replace(kSpec, '\n', '\r')), kRun, 0, Ok()},
      {"S19", "NUL byte in a cell", M(SpecSub("10,1e-6", std::string("10,1e-6\0" "5", 9))), kRun, 3, AtSpecFile()},
      {"S20", "semicolon separated", M(Replace(kSpec, ',', ';')), kRun, 3, AtSpecFile(), {"spec.csv:"}},
      {"S21", "grid outside the data (extrapolation: error)", M("f_hz,z\n0.5,1e-6\n1,1e-6\n3,1e-6\n"), kRun, 3,
       At("grid: |{type", "grid"), {"source 'noise' is defined over [0.5, 3] Hz only", "keep the grid inside"}},
      {"S21c", "grid outside the data: deb check says so too", M("f_hz,z\n0.5,1e-6\n1,1e-6\n3,1e-6\n"),
       "check b.yaml", 3, At("grid: |{type", "grid"), {"source 'noise' is defined over [0.5, 3] Hz only"}},
      {"S21d", "automatic grid without a range: stays inside the data (valid)",
       M("grid: {type: log, min_hz: 1, max_hz: 100, points: 50}", "grid: {type: auto}", kSpec), kRun, 0, Ok()},
      {"S21e", "automatic grid, a band beyond the data",
       With(Budget(Sub(Sub(kMeasured, "grid: {type: log, min_hz: 1, max_hz: 100, points: 50}", "grid: {type: auto}"),
                  "\noutputs:\n", "\nbands:\n  - [0.1, 10]\noutputs:\n")),
            "spec.csv", kSpec),
       kRun, 3, At("spectrum: |{type: measured", "sources[0].spectrum"),
       {"defined over [0.5, 200] Hz only", "keep them inside that range"}},
      {"S24", "file unit not the source's quantity", M("# unit: m\n" + kSpec), kRun, 3, At("unit: |N", "sources[0].unit")},
      {"S25", "column selection not in the file",
       M("{type: measured, file: spec.csv}", "{type: measured, file: spec.csv, columns: [nosuch]}", kSpec), kRun, 3,
       At("columns: |[nosuch]", "sources[0].spectrum.columns")},
      {"S26", "denormal first frequency 1e-320 (valid)", M("f_hz,z\n1e-320,1e-6\n" + kSpecRows), kRun, 0, Ok()},
      {"S27", "PSD 1e308", M("f_hz,z\n0.5,1e308\n1,1e308\n10,1e308\n200,1e308\n"), kRun, 3,
       At("{name: c1", "contributors[0]")},
      {"S28+", "spectrum file missing", Budget(kMeasured), kRun, 3, AtSpecFile(), {"spec.csv"}},
      {"X01", "file: /etc/passwd (content must not be echoed, D14)",
       Budget(Sub(kMeasured, "file: spec.csv", "file: /etc/passwd")), kRun, 3,
       At("file: |/etc/passwd", "sources[0].spectrum.file"), {}, {"root:x:0:0"}, "", "", 0, CheckNoPasswdLine},
      {"X07", "file: ../ traversal to /etc/passwd (D14)",
       Budget(Sub(kMeasured, "file: spec.csv", "file: ../../../../../../../../../../etc/passwd")), kRun, 3,
       At("file: |../../", "sources[0].spectrum.file"), {}, {"root:x:0:0"}, "", "", 0, CheckNoPasswdLine},
      {"X02", "spectrum file is a FIFO without a writer (D12)", Budget(kMeasured), kRun, 3, AtSpecFile(), {kNotRegular}, {},
       "mkfifo spec.csv", "", 20},
      {"X03", "spectrum file /dev/zero (D12)", Budget(Sub(kMeasured, "file: spec.csv", "file: /dev/zero")), kRun, 3,
       At("file: |/dev/zero", "sources[0].spectrum.file"), {kNotRegular}, {}, "", "", 20},
      {"X05", "spectrum file /dev/urandom", Budget(Sub(kMeasured, "file: spec.csv", "file: /dev/urandom")), kRun, 3,
       At("file: |/dev/urandom", "sources[0].spectrum.file"), {}, {}, "", "", 20},
      {"X06", "spectrum file is a directory (D12)", Budget(Sub(kMeasured, "file: spec.csv", "file: sub")), kRun, 3,
       At("file: |sub", "sources[0].spectrum.file"), {kNotRegular}, {}, "mkdir sub", "", 20},
      {"X24", "spectrum file /proc/self/mem", Budget(Sub(kMeasured, "file: spec.csv", "file: /proc/self/mem")), kRun, 3,
       At("file: |/proc/self/mem", "sources[0].spectrum.file"), {}, {}, "", "", 20},
  };
}

// ---- S: spectrum CSVs through deb spectrum ---------------------------------
[[gnu::noinline]] std::vector<Case> SpectrumCsvCommandCases() {
  return {
      {"S29+", "spectrum convert, valid (baseline, with plots)", {{"spec.csv", kSpec}},
       "spectrum convert spec.csv --unit N --to N -o c.csv", 0, Ok()},
      {"S30", "spectrum convert: empty file", {{"spec.csv", ""}}, "spectrum convert spec.csv --unit N --to N -o c.csv", 3,
       Names("spec.csv")},
      {"S31", "spectrum convert: --to an incompatible unit", {{"spec.csv", kSpec}},
       "spectrum convert spec.csv --unit N --to m -o c.csv", 3, Names("cannot convert")},
      {"S32", "spectrum bands: header only", {{"spec.csv", "# unit: um/s\nf_hz,z\n"}}, "spectrum bands spec.csv -o bands.csv",
       3, Names("spec.csv")},
      {"S32+", "spectrum bands: non-numeric cell", {{"spec.csv", "# unit: um/s\n" + SpecSub("10,1e-6", "10,abc")}},
       "spectrum bands spec.csv -o bands.csv", 3, Names("spec.csv:7:4:")},
      {"S33", "spectrum convert --from-bands: negative RMS", {{"spec.csv", "# unit: um/s\nf_hz,z\n1,0.1\n1.25,-1\n1.6,0.1\n"}},
       "spectrum convert --from-bands spec.csv -o c.csv", 3, Names("spec.csv:4:")},
      {"S34", "spectrum convert: -o is an existing directory (D20)", {{"spec.csv", kSpec}, {"outdir/keep.txt", "keep\n"}},
       "spectrum convert spec.csv --unit N --to N -o outdir", 4, Names("outdir")},
      {"S34b", "spectrum convert: -o into a missing directory (D20)", {{"spec.csv", kSpec}},
       "spectrum convert spec.csv --unit N --to N -o missing/c.csv", 4, Names("missing")},
      {"S34d", "spectrum convert --no-plots: -o into a missing directory (D20)", {{"spec.csv", kSpec}},
       "spectrum convert spec.csv --unit N --to N --no-plots -o missing/c.csv", 4, Names("missing")},
      {"S34e", "spectrum convert: --plot into a missing directory (D20)", {{"spec.csv", kSpec}},
       "spectrum convert spec.csv --unit N --to N -o c.csv --plot missing/c.png", 4, Names("missing")},
      {"S34c", "spectrum reference: -o into a missing directory (D20)", {},
       "spectrum reference nlnm -o missing/nlnm.csv", 4, Names("missing")},
      {"S35", "spectrum convert -o out.png (CSV and plot of one name)", {{"spec.csv", kSpec}},
       "spectrum convert spec.csv --unit N --to N -o out.png", 3, Names("out.png")},
      {"S36+", "spectrum bands on a FIFO (D12)", {}, "spectrum bands spec.csv -o bands.csv", 3, Names("spec.csv"),
       {kNotRegular}, {}, "mkfifo spec.csv", "", 20},
      {"S37+", "spectrum convert of a CR-only file (D23)", {{"spec.csv", Replace("# unit: N\n" + kSpec, '\n', '\r')}},
       "spectrum convert spec.csv --to N --no-plots -o c.csv", 0, Ok(), {}, {}, "", "", 0, CheckCrRowsRead},
      {"S38+", "spectrum convert of a BOM-prefixed headerless file keeps every row (D11)", {{"spec.csv", kBom + kSpecRows}},
       "spectrum convert spec.csv --unit N --to N --no-plots -o c.csv", 0, Ok(), {}, {}, "", "", 0, CheckBomRowKept},
  };
}

// ---- T: time series --------------------------------------------------------
[[gnu::noinline]] std::vector<Case> TimeSeriesCases() {
  return {
      {"T00", "valid CSV time series (baseline)", {{"b.yaml", kTs}, {"rec.csv", RecCsv()}}, kRun, 0, Ok()},
      {"T00r", "valid raw float64 time series (baseline)", {{"b.yaml", kRaw}, {"rec.raw", RawF64(Noise(4096, 1))}}, kRun, 0,
       Ok()},
      {"T01", "raw float64 file of 4097 bytes", {{"b.yaml", kRaw}, {"rec.raw", RawF64(Noise(512, 1)) + "x"}}, kRun, 3,
       At("file: |rec.raw", "sources[0].spectrum.file")},
      {"T02", "raw with rate_hz: 0", {{"b.yaml", Sub(kRaw, "rate_hz: 1000", "rate_hz: 0")}, {"rec.raw", RawF64(Noise(4096, 1))}},
       kRun, 3, At("rate_hz: |0", "sources[0].spectrum.rate_hz")},
      {"T03", "CSV with a single sample", {{"b.yaml", kTs}, {"rec.csv", "# rate_hz: 1000\nx\n0.5\n"}}, kRun, 3,
       At("spectrum: |{type: timeseries", "sources[0].spectrum")},
      {"T04", "CSV without any rate", {{"b.yaml", kTs}, {"rec.csv", Sub(RecCsv(), "# rate_hz: 1000\n", "")}}, kRun, 3,
       At("file: |rec.csv", "sources[0].spectrum.file")},
      {"T05", "CSV time column non-uniform",
       {{"b.yaml", kTs}, {"rec.csv", RecTimed(4096, [](int i) { return i == 50 ? 0.0505 : i * 0.001; })}}, kRun, 3,
       At("file: |rec.csv", "sources[0].spectrum.file"), {"rec.csv:52:1:"}},
      {"T06", "CSV time column decreasing",
       {{"b.yaml", kTs}, {"rec.csv", RecTimed(4096, [](int i) { return i == 2 ? -0.001 : i * 0.001; })}}, kRun, 3,
       At("file: |rec.csv", "sources[0].spectrum.file"), {"rec.csv:4:1:"}},
      {"T07", "CSV time stamps 5e-324 apart",
       {{"b.yaml", kTs}, {"rec.csv", RecTimed(64, [](int i) { return i * 4.9406564584124654e-324; })}}, kRun, 3,
       At("file: |rec.csv", "sources[0].spectrum.file")},
      {"T08", "segment_length longer than the recording",
       {{"b.yaml", Ts("{type: timeseries, file: rec.csv, segment_length: 65536}")}, {"rec.csv", RecCsv()}}, kRun, 3,
       At("spectrum: |{type: timeseries", "sources[0].spectrum")},
      {"T09", "raw empty file", {{"b.yaml", kRaw}, {"rec.raw", ""}}, kRun, 3, At("file: |rec.raw", "sources[0].spectrum.file")},
      {"T10", "raw file with a NaN sample", {{"b.yaml", kRaw}, {"rec.raw", RawWithNan()}}, kRun, 3,
       At("file: |rec.raw", "sources[0].spectrum.file")},
      {"T11", "segment_length 4", {{"b.yaml", Ts("{type: timeseries, file: rec.csv, segment_length: 4}")}, {"rec.csv", RecCsv()}},
       kRun, 3, At("segment_length: |4", "sources[0].spectrum.segment_length")},
      {"T12", "overlap 1.0", {{"b.yaml", Ts("{type: timeseries, file: rec.csv, overlap: 1.0}")}, {"rec.csv", RecCsv()}}, kRun,
       3, At("spectrum: |{type: timeseries", "sources[0].spectrum")},
      {"T14", "CSV '# rate_hz: 0'", {{"b.yaml", kTs}, {"rec.csv", Sub(RecCsv(), "rate_hz: 1000", "rate_hz: 0")}}, kRun, 3,
       At("file: |rec.csv", "sources[0].spectrum.file"), {"rec.csv:1:"}},
      {"T15", "raw file_channels: 0",
       {{"b.yaml", Sub(kRaw, "file_channels: 1}", "file_channels: 0}")}, {"rec.raw", RawF64(Noise(4096, 1))}},
       kRun, 3, At("file: |rec.raw", "sources[0].spectrum.file")},
      {"T16", "raw file_channels: 2000000000",
       {{"b.yaml", Sub(kRaw, "file_channels: 1}", "file_channels: 2000000000}")},
        {"rec.raw", RawF64(Noise(4096, 1))}},
       kRun, 3, At("file_channels: |2000000000", "sources[0].spectrum.file_channels"), {}, {}, "", "", 30},
      {"T17", "raw format float16", {{"b.yaml", Sub(kRaw, "float64", "float16")}, {"rec.raw", RawF64(Noise(4096, 1))}}, kRun,
       3, At("float16", "sources[0].spectrum.format")},
      {"T18", "12 bytes given as float64", {{"b.yaml", kRaw}, {"rec.raw", std::string(12, '\0')}}, kRun, 3,
       At("file: |rec.raw", "sources[0].spectrum.file")},
      {"T19", "all-zero recording (valid, RMS 0)", {{"b.yaml", kTs}, {"rec.csv", RecCsv(4096, 0.0)}}, kRun, 0, Ok()},
      {"T20", "overlap 0.999999 (valid)",
       {{"b.yaml", Ts("{type: timeseries, file: rec.csv, overlap: 0.999999}")}, {"rec.csv", RecCsv()}}, kRun, 0, Ok()},
      {"T21", "samples 1e300", {{"b.yaml", kTs}, {"rec.csv", RecCsv(4096, 1e300)}}, kRun, 3,
       At("file: |rec.csv", "sources[0].spectrum.file")},
      {"X04", "raw time series file /dev/zero (D12)",
       Budget(Ts("{type: timeseries, file: /dev/zero, format: float64, rate_hz: 1000, file_channels: 1}")), kRun, 3,
       At("file: |/dev/zero", "sources[0].spectrum.file"), {kNotRegular}, {}, "", "", 20},
      {"T22+", "CSV time series file is a FIFO (D12)", Budget(kTs), kRun, 3, At("file: |rec.csv", "sources[0].spectrum.file"),
       {kNotRegular}, {}, "mkfifo rec.csv", "", 20},
      {"T23+", "time series file is a directory (D12)", Budget(kTs), kRun, 3,
       At("file: |rec.csv", "sources[0].spectrum.file"), {kNotRegular}, {}, "mkdir rec.csv", "", 20},
      {"C27", "spectrum welch: raw file without --rate", {{"rec.raw", RawF64(Noise(4096, 1))}},
       "spectrum welch rec.raw --format float64 -o psd.csv", 3, Names("rec.raw")},
      {"C28", "spectrum welch --rate 0", {{"rec.raw", RawF64(Noise(4096, 1))}},
       "spectrum welch rec.raw --format float64 --rate 0 -o psd.csv", 2, Usage()},
      {"C29", "spectrum welch --rate -5", {{"rec.raw", RawF64(Noise(4096, 1))}},
       "spectrum welch rec.raw --format float64 --rate -5 -o psd.csv", 2, Usage()},
      {"C30", "spectrum welch --segment 3", {{"rec.csv", RecCsv()}}, "spectrum welch rec.csv --segment 3 -o psd.csv", 3,
       Names("segment")},
      {"C31", "spectrum welch --file-channels 0", {{"rec.raw", RawF64(Noise(4096, 1))}},
       "spectrum welch rec.raw --format float64 --rate 1000 --file-channels 0 -o psd.csv", 3, Names("rec.raw")},
      {"C32", "spectrum frf: --input not a channel", {{"rec.csv", RecCsv()}},
       "spectrum frf rec.csv --input F --outputs x -o frf.csv", 3, Names("'F'")},
      {"C33", "spectrum selfnoise with 1 sensor", {{"rec.csv", Rec3("a,b,c")}},
       "spectrum selfnoise rec.csv --sensors a -o noise.csv", 3, Names("--sensors")},
      {"C34", "spectrum reference: bogus model", {}, "spectrum reference xlnm -o r.csv", 3, Names("xlnm")},
      {"C35", "spectrum welch --confidence 1.5", {{"rec.csv", RecCsv()}},
       "spectrum welch rec.csv --confidence 1.5 -o psd.csv", 3, Names("confidence")},
      {"C35+", "spectrum welch of /dev/zero as raw (D12)", {},
       "spectrum welch /dev/zero --format float64 --rate 1000 -o psd.csv", 3, Names("/dev/zero"), {kNotRegular}, {}, "",
       "", 20},
      {"C35++", "spectrum welch, valid (baseline, with plots)", {{"rec.csv", RecCsv()}}, "spectrum welch rec.csv -o psd.csv",
       0, Ok()},
  };
}

// ---- F: FRF tables ---------------------------------------------------------
[[gnu::noinline]] std::vector<Case> FrfTableCases() {
  return {
      {"F00", "valid FRF (baseline)", Fr(kFrfTable), kRun, 0, Ok()},
      {"F01", "no header row", Fr(kFrfTable.substr(kFrfTable.find('\n') + 1)), kRun, 3, AtFrfFile(), {"frf.csv:1:1:"}},
      {"F02", "column not named OUTPUT/INPUT.PART", Fr(Sub(kFrfTable, "y/u.mag", "mag")), kRun, 3, AtFrfFile(),
       {"frf.csv:1:"}},
      {"F03", "phase column missing", Fr("f_hz, y/u.mag\n0.5, 0.01\n1, 0.01\n200, 0.01\n"), kRun, 3, AtFrfFile(),
       {"frf.csv:1:"}},
      {"F04", "negative magnitude", Fr(Sub(kFrfTable, "5, 0.01, -5", "5, -0.01, -5")), kRun, 3, AtFrfFile(), {"frf.csv:5:"}},
      {"F04+", "a column naming a misspelt input of the path",
       {{"b.yaml", Sub(kFrf, "file: frf.csv\n", "file: frf.csv\n    outputs: [y]\n    inputs: [force]\n")},
        {"frf.csv", Sub(Sub(kFrfTable, "y/u.mag", "y/forc.mag"), "y/u.phase_deg", "y/forc.phase_deg")}},
       kRun, 3, AtFrfFile(), {"frf.csv:1:", "input 'forc' (did you mean 'force'?)"}},
      {"F05", "db 1e6", Fr("f_hz, y/u.db, y/u.phase_deg\n0.5, -40, 0\n8, 1e6, 0\n200, -40, 0\n"), kRun, 3, AtFrfFile()},
      {"F06", "non-increasing frequency", Fr(Sub(kFrfTable, "10, 0.01, -10", "5, 0.01, -10")), kRun, 3, AtFrfFile(),
       {"frf.csv:6:1:"}},
      {"F07", "single row", Fr("f_hz, y/u.mag, y/u.phase_deg\n1, 0.01, 0\n"), kRun, 3, AtFrfFile(), {"1 data rows"}},
      {"F08", "coherence column only", Fr("f_hz, y/u.coherence\n0.5, 1\n1, 1\n200, 1\n"), kRun, 3, AtFrfFile()},
      {"F09", "duplicate column", Fr(Sub(kFrfTable, "y/u.phase_deg", "y/u.mag")), kRun, 3, AtFrfFile(), {"frf.csv:1:"}},
      {"F10", "phase_deg 1e300 (valid)", Fr("f_hz, y/u.mag, y/u.phase_deg\n0.5, 1, 1e300\n200, 1, 1e300\n"), kRun, 0, Ok()},
      {"F11", "re/im 1e308", Fr("f_hz, y/u.re, y/u.im\n0.5, 1e308, 1e308\n200, 1e308, 1e308\n"), kRun, 3,
       At("{name: c1", "contributors[0]")},
      {"F12", "outputs: list not in the file",
       {{"b.yaml", Sub(kFrf, "    file: frf.csv\n", "    file: frf.csv\n    outputs: [q]\n")}, {"frf.csv", kFrfTable}}, kRun,
       3, AtFrfFile()},
      {"F13", "FRF file missing", Budget(kFrf), kRun, 3, AtFrfFile(), {"frf.csv"}},
      {"F14", "FRF with the grid outside its data",
       Fr("f_hz, y/u.mag, y/u.phase_deg\n3.36375, 0.01, 0\n10, 0.01, -10\n20.5724, 0.01, -20\n"), kRun, 3,
       At("grid: |{type", "grid"), {"path 'plant' (measured data) is defined over [3.36375, 20.5724] Hz only"}},
      {"F15", "mag and db for one entry", Fr("f_hz, y/u.mag, y/u.db, y/u.phase_deg\n0.5, 1, 0, 0\n200, 1, 0, 0\n"), kRun, 3,
       AtFrfFile(), {"frf.csv:1:"}},
      {"F17+", "FRF file is a directory (D12)", Budget(kFrf), kRun, 3, AtFrfFile(), {kNotRegular}, {}, "mkdir frf.csv", "",
       20},
      {"F18+", "FRF file is a FIFO (D12)", Budget(kFrf), kRun, 3, AtFrfFile(), {kNotRegular}, {}, "mkfifo frf.csv", "", 20},
      {"F19+", "FRF file /dev/zero (D12)", Budget(Sub(kFrf, "file: frf.csv", "file: /dev/zero")), kRun, 3,
       At("file: |/dev/zero", "paths[0].file"), {kNotRegular}, {}, "", "", 20},
      {"F20+", "non-scalar key inside an FRF path (D05a)",
       {{"b.yaml", Sub(kFrf, "    file: frf.csv\n", "    file: frf.csv\n    ? [a] : 1\n")}, {"frf.csv", kFrfTable}}, kRun, 3,
       At("", "paths[0]")},
  };
}

// ---- M: MATLAB .mat files --------------------------------------------------
[[gnu::noinline]] std::vector<Case> MatFileCases() {
  return {
      {"M00+", "state space from a .mat (baseline)", {{"b.yaml", kMat}, {"plant.mat", PlantMat()}}, kRun, 0, Ok()},
      {"M01+", "a .mat without B", {{"b.yaml", kMat}, {"plant.mat", PlantMat(false)}}, kRun, 3, AtMatFile(),
       {"no variable 'B' in the MAT-file (it holds A, C)"}},
      {"M02+", "text saved as plant.mat", {{"b.yaml", kMat}, {"plant.mat", std::string(200, 'A') + "\n"}}, kRun, 3,
       AtMatFile(), {"not a MAT-file of version 5, 7 or 7.3"}},
      {"M03+", "a truncated .mat", {{"b.yaml", kMat}, {"plant.mat", PlantMat().substr(0, 150)}}, kRun, 3, AtMatFile(),
       {"truncated or damaged"}},
      {"M04+", ".mat is a directory (D12)", Budget(kMat), kRun, 3, AtMatFile(), {kNotRegular}, {}, "mkdir plant.mat", "",
       20},
      {"M05+", ".mat is a FIFO (D12)", Budget(kMat), kRun, 3, AtMatFile(), {kNotRegular}, {}, "mkfifo plant.mat", "", 20},
      {"M06+", "file: and A: in one state_space path",
       {{"b.yaml", Sub(kMat, "file: plant.mat\n", "file: plant.mat\n    A: [[1]]\n")}, {"plant.mat", PlantMat()}}, kRun,
       3, At("A: |[[1]]", "paths[0].A"), {"not both"}},
  };
}

// ---- N: Nastran result files (modal paths) ---------------------------------
[[gnu::noinline]] std::vector<Case> NastranCases() {
  return {
      {"N00+", "modes from an OP2 file Nastran wrote (baseline)", Op2(BeamOp2()), kRun, 0, Ok()},
      {"N01+", "OP2 truncated inside its header", Op2(BeamOp2().substr(0, 50)), kRun, 3, AtOp2File(),
       {"beam.op2: byte ", "truncated?"}},
      {"N02+", "OP2 truncated inside LAMA", Op2(BeamOp2().substr(0, 10500)), kRun, 3, AtOp2File(),
       {"beam.op2: byte 10400: a record of 584 bytes runs past the file's end"}},
      {"N03+", "OP2 truncated inside the eigenvectors", Op2(BeamOp2().substr(0, 13000)), kRun, 3, AtOp2File(),
       {"beam.op2: byte ", "truncated?"}},
      {"N04+", "a record's length markers disagree", Op2(Op2With(10400, std::string("\x49\x02", 2))), kRun, 3,
       AtOp2File(), {"beam.op2: byte 10400: a record's length markers disagree: 585 before it"}},
      {"N05+", "an OP2 without eigenvectors", Op2(Op2With(11392, "OUGX")), kRun, 3, AtOp2File(),
       {"no eigenvectors (OUGV1 or BOUGV1)", "The file holds PVT0, CASECC"}},
      {"N06+", "an OP2 without eigenvalues", Op2(Op2With(10216, "XAMA")), kRun, 3, AtOp2File(),
       {"no eigenvalue table (LAMA)"}},
      {"N07+", "a grid not in the file", Op2(BeamOp2(), Sub(kNastran, "y: \"11:T3\"", "y: \"99:T3\"")), kRun, 3,
       AtOp2File(), {"grid 99 (of 99:T3) is not in OUGV1, which holds 12 grid(s): 1-12"}},
      {"N08+", "a component Nastran has not", Op2(BeamOp2(), Sub(kNastran, "u: \"11:T3\"", "u: \"11:T9\"")), kRun, 3,
       At("u: |\"11:T9\"", "paths[0].inputs.u"), {"'11:T9' is not a Nastran DOF"}},
      {"N09+", "complex modes (a punch file of a fluid-structure run)",
       {{"b.yaml", Sub(kNastran, "beam.op2", "fsi.pch")},
        {"fsi.pch", ReadAll(fs::path(DEB_SOURCE_DIR) / "tests/data/nastran/fsi.pch")}},
       kRun, 3, At("file: |fsi.pch", "paths[0].file"), {"fsi.pch:5: complex eigenvectors"}},
      {"N10+", "OP2 is a FIFO (D12)", Budget(kNastran), kRun, 3, AtOp2File(), {kNotRegular}, {}, "mkfifo beam.op2", "",
       20},
      {"N11+", "OP2 of zeros (no Fortran records)", Op2(std::string(4096, '\0')), kRun, 3, AtOp2File(),
       {"neither a Nastran OP2 file"}},
  };
}

// ---- P: modes as OP4 matrices ----------------------------------------------
[[gnu::noinline]] std::vector<Case> Op4Cases() {
  return {
      {"P00+", "one mode from OP4 matrices (baseline)", Op4Modal(ModesOp4()), kRun, 0, Ok()},
      {"P01+", "a matrix the file has not", Op4Modal(ModesOp4(), Sub(kOp4Modal, "lambda: LAMA", "lambda: KHH")), kRun,
       3, AtOp4Matrices(), {"m.op4: no matrix 'KHH' in the OP4 file", "PHIG, LAMA"}},
      {"P02+", "more rows named than the eigenvectors have",
       Op4Modal(ModesOp4(), Sub(kOp4Modal, "rows: [\"1:T1\"]", "rows: [1]")), kRun, 3, AtOp4Matrices(),
       {"6 row DOF(s) given (rows:) but 'PHIG' has 1 rows"}},
      {"P03+", "an OP4 file cut inside a column", Op4Modal(ModesOp4().substr(0, 100)), kRun, 3,
       At("file: |m.op4", "paths[0].file"), {"m.op4:"}},
      {"P04+", "no rows: the OP4 file does not name them", Op4Modal(ModesOp4(), Sub(kOp4Modal, "    rows: [\"1:T1\"]\n", "")),
       kRun, 3, At("- |name: plant", "paths[0]"), {"missing 'rows'"}},
  };
}

// ---- Q: uncertainty studies ------------------------------------------------
[[gnu::noinline]] std::vector<Case> UncertaintyCases() {
  return {
      {"Q00", "an uncertainty study (baseline)", Budget(kUncertain), "uncertainty b.yaml -n 20 --no-plots", 0, Ok()},
      {"Q01", "sigma below zero", Budget(Sub(kUncertain, "{uniform: {min: 0.5, max: 2}}", "{normal: {sigma: -1}}")),
       "uncertainty b.yaml -n 20 --no-plots", 3, At("normal: |{sigma: -1}", "parameters.lvl.distribution.normal"),
       {"sigma -1 must be finite and > 0"}},
      {"Q02", "min above max", Budget(Sub(kUncertain, "min: 0.5, max: 2", "min: 2, max: 0.5")), kRun, 3,
       At("uniform: |{min: 2", "parameters.lvl.distribution.uniform"), {"min 2 must be below max 0.5"}},
      {"Q03", "--samples 0", Budget(kUncertain), "uncertainty b.yaml -n 0", 2, Usage()},
      {"Q04", "--samples above the limit", Budget(kUncertain), "uncertainty b.yaml -n 1000001", 2, Usage()},
      {"Q05", "--method unknown", Budget(kUncertain), "uncertainty b.yaml --method quasi", 2, Usage()},
      {"Q06", "a budget without distributions", Budget(kBase), "uncertainty b.yaml -n 20", 3, Names("b.yaml"),
       {"no parameter has a distribution"}},
      {"Q07", "a correlation of a parameter without a distribution",
       Budget(Sub(kUncertain, "grid:", "correlations: [{between: [lvl, k], rho: 0.5}]\ngrid:")), kRun, 3,
       At("lvl, |k]", "correlations[0].between[1]"), {"'k' is not a parameter with a distribution"}},
      {"Q08", "a sample whose budget is invalid (a negative PSD level)",
       Budget(Sub(kUncertain, "{uniform: {min: 0.5, max: 2}}", "{normal: {sigma: 2}}")),
       "uncertainty b.yaml -n 50 --no-plots", 3, Names("sample "), {"lvl = -"}},
  };
}

// ---- O: design optimisation ------------------------------------------------
[[gnu::noinline]] std::vector<Case> OptimiseCases() {
  return {
      {"O00", "an optimisation (baseline)", Budget(kOptimise), "optimise b.yaml --vary k --no-plots", 0, Ok()},
      {"O01", "--vary a parameter that is not one", Budget(kOptimise), "optimise b.yaml --vary kk --no-plots", 3,
       Names("b.yaml"), {"--vary kk: no parameter of that name (did you mean 'k'?)"}},
      {"O02", "--vary a parameter without bounds", Budget(kOptimise), "optimise b.yaml --vary c --no-plots", 3,
       Names("b.yaml"), {"--vary c: the parameter has no bounds"}},
      {"O03", "min above max", Budget(Sub(kOptimise, "min: 50, max: 400", "min: 400, max: 50")), kRun, 3,
       At("max: |50}", "parameters.k.max"), {"max 50 must be above min 400"}},
      {"O04", "a value outside its bounds", Budget(Sub(kOptimise, "min: 50, max: 400", "min: 150, max: 400")), kRun, 3,
       At("value: |100", "parameters.k.value"), {"lies outside [min, max]"}},
      {"O05", "--objective an output the budget has not", Budget(kOptimise),
       "optimise b.yaml --vary k --objective q --no-plots", 3, Names("--objective q"), {"no output of that name"}},
      {"O06", "--vary missing", Budget(kOptimise), "optimise b.yaml", 2, Usage()},
      {"O07", "--starts 0", Budget(kOptimise), "optimise b.yaml --vary k --starts 0", 2, Usage()},
      {"O08", "a weighted-sum objective with a weight that is not > 0", Budget(kOptimise),
       "optimise b.yaml --vary k --objective 'y + -2*y' --no-plots", 3, Names("--objective 'y + -2*y'"),
       {"weight -2 must be a finite number > 0"}},
  };
}

// ---- U: universal files (UFF dataset 58) -----------------------------------
[[gnu::noinline]] std::vector<Case> UffCases() {
  return {
      {"U00+", "a PSD from a universal file (baseline)", Uff(PsdUff()), kRun, 0, Ok()},
      {"U01+", "an unknown function type", Uff(Sub(PsdUff(), "\n    9         0    0", "\n   99         0    0")),
       kRun, 3, AtUffFile(), {"psd.uff:8:1: dataset #1 (58), record 6: function type 99 is unknown"}},
      {"U02+", "a point count that disagrees with the data", Uff(Sub(PsdUff(), "      3201 ", "      3202 ")), kRun, 3,
       AtUffFile(), {"psd.uff:", "dataset #1 (58)"}},
      {"U03+", "a universal file cut inside its data", Uff(PsdUff().substr(0, 60000)), kRun, 3, AtUffFile(),
       {"psd.uff:", "dataset #1 (58)"}},
      {"U04+", "a number that is not one", Uff(Sub(PsdUff(), "1.255863E-06", "1.255863X-06")), kRun, 3, AtUffFile(),
       {"psd.uff:14:54: dataset #1 (58), record 12: '1.255863X-06' is not a number"}},
  };
}

// ---- A: deb report on a crafted result.h5 (this audit's A cases) -----------
[[gnu::noinline]] std::vector<Case> CraftedStoreCases() {
  return {
      {"A00+", "redraw of an untouched store (baseline)", Store([](hid_t) {}), kReport, 0, Ok()},
      {"A13a", "f_hz stored externally in /etc/passwd (N01)",
       Store([](hid_t f) { PutExternal(f, "result/grid/f_hz", "/etc/passwd"); }), kReport, 3, AtStore(),
       {"object 'result/grid/f_hz' keeps its values in another file"}, {"root"}, "", "", 0, CheckNoPasswdLine},
      {"A13b", "a PSD stored externally in a FIFO: no hang (N01)",
       Store([](hid_t f) { PutExternal(f, "result/outputs/0/contributors/0/psd", "fifo"); }), kReport, 3, AtStore(),
       {"keeps its values in another file"}, {}, "mkfifo fifo", "", 20},
      {"A13c", "a PSD stored externally in /dev/zero (N01)",
       Store([](hid_t f) { PutExternal(f, "result/outputs/0/contributors/0/psd", "/dev/zero"); }), kReport, 3,
       AtStore(), {"keeps its values in another file"}},
      {"A13d", "a PSD stored externally in a file of plausible values (N01)",
       With(Store([](hid_t f) { PutExternal(f, "result/outputs/0/contributors/0/psd", "values.bin"); }), "values.bin",
            std::string(50 * 8, '\x3e')),
       kReport, 3, AtStore(), {"object 'result/outputs/0/contributors/0/psd' keeps its values in another file"}},
      {"A13e", "schema_version stored externally in /proc/self/environ (N01)",
       Store([](hid_t f) { PutExternal(f, "schema_version", "/proc/self/environ"); }), kReport, 3, AtStore(),
       {"object 'schema_version' keeps its values in another file"}, {"schema version"}},
      {"A14b", "budget/text an external link to another file (N01)",
       With(Store([](hid_t f) { PutExternalLink(f, "budget/text", "other.h5", "budget/text"); }), "other.h5",
            BaseStore()),
       kReport, 3, AtStore(), {"object 'budget/text' is an external link"}},
      {"A14e+", "a soft link in a store (N01)", Store([](hid_t f) { PutSoftLink(f, "budget/text", "/budget/name"); }),
       kReport, 3, AtStore(), {"object 'budget/text' is a soft link"}},
      {"A14f+", "f_hz a virtual dataset of another file (N01)",
       With(Store([](hid_t f) { PutVirtual(f, "result/grid/f_hz", 50, "other.h5", "result/grid/f_hz"); }), "other.h5",
            BaseStore()),
       kReport, 3, AtStore(), {"object 'result/grid/f_hz' is a virtual dataset"}},
      {"A10a", "panel_starts [0] on a grid without panels (N04)",
       Store([](hid_t f) { PutNumbers(f, "result/grid/panel_starts", {0}); }), kReport, 3, AtStore(),
       {"object 'result/grid/panel_starts'", "Lobatto"}, {"internal error"}},
      {"A10d", "panel_starts decreasing [6, 0] (N04)",
       Store([](hid_t f) { PutNumbers(f, "result/grid/panel_starts", {6, 0}); }), kReport, 3, AtStore(),
       {"object 'result/grid/panel_starts'"}, {"internal error"}},
      {"A16b", "an output variance of -1, with plots (N04)",
       Store([](hid_t f) { PutNumber(f, "result/outputs/0/variance", -1); }), "report r --format png", 3, AtStore(),
       {"object 'result/outputs/0/variance' holds -1, which must be >= 0"}, {"internal error"}},
      {"A16d", "a total PSD all negative (N14)",
       Store([](hid_t f) { PutNumbers(f, "result/outputs/0/total_psd", std::vector<double>(50, -1.0)); }), kReport, 3,
       AtStore(), {"object 'result/outputs/0/total_psd' holds -1 at element 0"}},
      {"A16f", "rms_max 0 (N14)", Store([](hid_t f) { PutNumber(f, "result/outputs/0/rms_max", 0); }), kReport, 3,
       AtStore(), {"object 'result/outputs/0/rms_max' holds the requirement 0, which must be > 0"}},
      {"A16g", "rms_max -5 (N14)", Store([](hid_t f) { PutNumber(f, "result/outputs/0/rms_max", -5); }), kReport, 3,
       AtStore(), {"holds the requirement -5"}},
      {"A05a", "f_hz declared as 250 M doubles, never written (N09)",
       Store([](hid_t f) { PutDeclared(f, "result/grid/f_hz", {250'000'000}); }), kReport, 3, AtStore(),
       {"object 'result/grid/f_hz' declares 250000000 values, more than the 5000000 it may hold"}, {}, "", "", 10},
      {"A05d", "gain2 declared [250000000 x 0] (N09)",
       Store([](hid_t f) { PutDeclared(f, "result/traces/paths/0/0/gain2", {250'000'000, 0}); }), kReport, 3,
       AtStore(), {"declares 250000000 rows, more than the 1 it may hold"}, {}, "", "", 10},
      {"A05f", "outputs/names declared as 250 M texts (N09)",
       Store([](hid_t f) { PutDeclared(f, "result/outputs/names", {250'000'000}, true); }), kReport, 3, AtStore(),
       {"object 'result/outputs/names' declares 250000000 values, more than the 100000"}, {}, "", "", 10},
      {"A05k", "tones declared [125000000 x 2] (N09)",
       Store([](hid_t f) { PutDeclared(f, "result/outputs/0/contributors/0/tones", {125'000'000, 2}); }), kReport, 3,
       AtStore(), {"declares 125000000 rows, more than the 10000"}, {}, "", "", 10},
      {"A05n+", "a PSD declared with its 50 values, never written (N09)",
       Store([](hid_t f) { PutDeclared(f, "result/outputs/0/total_psd", {50}); }), kReport, 3, AtStore(),
       {"declares 50 values, but the file holds 0 of them"}},
      {"A07b", "terminal escapes in the budget name (N14)",
       Store([](hid_t f) { PutText(f, "budget/name", "\x1b[31mred\a"); }), kReport, 3, AtStore(),
       {"object 'budget/name' holds the name"}, {"\x1b"}},
      {"A07e+", "terminal escapes in an output unit (N14)",
       Store([](hid_t f) { PutText(f, "result/outputs/0/unit", "nm\x1b[2J"); }), kReport, 3, AtStore(),
       {"object 'result/outputs/0/unit' holds a control character"}, {"\x1b"}},
      {"A12c", "a group path 20 levels deep (N14)",
       Store([](hid_t f) { PutText(f, "budget/contributors/0/group", "g0/g1/g2/g3/g4/g5/g6/g7/g8/g9/g10/g11/g12/g13/g14/g15/g16/g17/g18/g19"); }),
       "report r --format png", 3, AtStore(), {"object 'budget/contributors/0/group'", "20 levels, more than 16"}},
      {"A12d", "two outputs of one name (N14)", Store([](hid_t f) { PutText(f, "result/outputs/1/name", "z"); }),
       kReport, 3, AtStore(), {"object 'result/outputs/1/name' holds the name 'z', which another output has"}},
      {"A12e", "an empty output name (N14)", Store([](hid_t f) { PutText(f, "result/outputs/0/name", ""); }), kReport,
       3, AtStore(), {"holds an empty name"}},
      {"A12h", "a name that is not UTF-8 (N07)",
       Store([](hid_t f) { PutText(f, "result/outputs/0/name", "z\xff\xfe"); }), kReport, 3, AtStore(),
       {"object 'result/outputs/0/name' holds text where byte 0xff at character 2 is not UTF-8"}, {"internal error"}},
      {"A12i", "a group named total (N14)",
       Store([](hid_t f) { PutText(f, "result/outputs/0/contributors/0/group", "total"); }), "report r --format png", 3,
       AtStore(), {"object 'result/outputs/0/contributors/0/group'", "'total' is reserved"}},
      {"A03d", "schema as a fixed-length string (N14)", Store([](hid_t f) { PutFixedText(f, "schema", "deb-result"); }),
       kReport, 3, AtStore(), {"object 'schema' holds text of a fixed length, not text"}},
      {"A20+", "a damaged global heap entry of a text (N11)", DamagedHeapStore(kStoreBudget), kReport, 3,
       AtStore(), {"is damaged", "global heap"}},
  };
}

// ---- B: version 7.3 .mat files (HDF5) --------------------------------------
[[gnu::noinline]] std::vector<Case> Mat73Cases() {
  return {
      {"B12a", "v7.3: A stored externally in /etc/passwd (N01)",
       {{"b.yaml", kMat}, {"plant.mat", PlantMat73([](hid_t f) { PutExternal(f, "A", "/etc/passwd"); })}}, kRun, 3,
       AtMatFile(), {"object 'A' keeps its values in another file"}, {"internal error"}, "", "", 0, CheckNoPasswdLine},
      {"B12b", "v7.3: A stored externally in a FIFO: no hang (N01)",
       {{"b.yaml", kMat}, {"plant.mat", PlantMat73([](hid_t f) { PutExternal(f, "A", "fifo"); })}}, kRun, 3,
       AtMatFile(), {"keeps its values in another file"}, {}, "mkfifo fifo", "", 20},
      {"B12h+", "v7.3: B an external link to another file (N01)",
       {{"b.yaml", kMat}, {"plant.mat", PlantMat73([](hid_t f) { PutExternalLink(f, "B", "other.mat", "B"); })},
        {"other.mat", PlantMat73([](hid_t) {})}},
       kRun, 3, AtMatFile(), {"object 'B' is an external link"}},
      {"B13+", "v5: a part of A claims 2 GB, in a file of 200 bytes (N17)",
       {{"b.yaml", kMat}, {"plant.mat", PlantMatLongPart()}}, kRun, 3, AtMatFile(),
       {"claims 2147483632 bytes, more than the variable holds"}, {}, "", "", 10},
      {"B06k", "a .mat with two variables named A (N15d)", {{"b.yaml", kMat}, {"plant.mat", PlantMatTwiceA()}}, kRun,
       3, AtMatFile(), {"holds two variables named 'A'"}},
      {"B14+", "a state-space .mat of 2001 states (N10)", {{"b.yaml", kMat}, {"plant.mat", PlantMatStates(2001)}}, kRun,
       3, AtMatFile(), {"2001 states, more than the 2000"}, {}, "", "", 20},
      {"B15+", "a transfer function of order 2001 (N10)", B("den: [1, 2, 100]", DenOfOrder(2001)), kRun, 3,
       At("den: |[1, 0", "paths[0].den"), {"2001 states, more than the 2000"}},
  };
}

// ---- UTF-8, extends, file-size limit ---------------------------------------
[[gnu::noinline]] std::vector<Case> Utf8AndLimitCases() {
  return {
      {"E10+", "a description in Latin-1 (N07)", B("description: bad-input catalogue base budget", "description: caf\xe9"),
       kRun, 3, At("description: |caf", "description"), {"byte 0xe9 at character 4 is not UTF-8"}},
      {"E11+", "a channel name with a byte 0xff (N07)",
       B("    unit: N\n    spectrum", "    unit: N\n    channels: [x\xff]\n    spectrum"), kRun, 3,
       At("channels: [|x", "sources[0].channels[0]"), {"is not UTF-8"}},
      {"E12+", "a spectrum CSV column name in Latin-1 (N07)", M("f_hz,caf\xe9\n" + kSpecRows), kRun, 3, AtSpecFile(),
       {"spec.csv:1:6:", "is not UTF-8"}},
      {"D05b", "an alias bomb in the base a budget extends: no hang (N12)",
       {{"b.yaml", "extends: base.yaml\nname: child\n"},
        {"base.yaml", Sub(kBase, "description: bad-input catalogue base budget", "description: " + AliasBomb("lol"))}},
       kRun, 3, Names("description"), {"expected a single value"}, {}, "", "", 10},
      {"D04e", "extends a shadow-like file: its line quoted at most 40 characters (N16)",
       {{"b.yaml", "extends: shadow\nname: child\n"},
        {"shadow", "root:$6$0123456789abcdef$0123456789abcdefghijklmnopqrstuvwxyz0123456789:19000:0:99999:7:::\n"}},
       kRun, 3, Names("unknown key"), {"unknown key 'root:$6$0123456789abcdef$0123456789abcde…'"},
       {"0123456789abcdefghijklmnopqrstuvwxyz0123456789"}},
      {"H01+", "a report larger than the file-size limit (ulimit -f): exit 4, no HDF5 error stack (N06)", B(),
       "run b.yaml --no-plots --out out", 4, Names("File too large"), {}, {"HDF5-DIAG", "internal error"}, "",
       "ulimit -f 20;"},
  };
}

// ---- C: command line -------------------------------------------------------
[[gnu::noinline]] std::vector<Case> CommandLineCases() {
  return {
      {"C01", "budget file missing", {}, "run nosuch.yaml", 2, Usage()},
      {"C02", "a directory given as budget", {}, "run dir", 2, Usage(), {}, {}, "mkdir dir"},
      {"C03", "--out onto an existing regular file (D02)", With(B(), "existing.txt", "keep me\n"),
       "run b.yaml --no-plots --out existing.txt", 4, Names("existing.txt"), {"not a report written by deb", "--force"}},
      {"C05", "--threads 0 (valid)", B(), "run b.yaml --no-plots --threads 0", 0, Ok()},
      {"C06", "--threads -1", B(), "run b.yaml --no-plots --threads -1", 2, Usage()},
      {"C07", "--threads 100000 (valid)", B(), "run b.yaml --no-plots --threads 100000", 0, Ok()},
      {"C08", "--threads abc", B(), "run b.yaml --no-plots --threads abc", 2, Usage()},
      {"C09", "--threads 99999999999", B(), "run b.yaml --no-plots --threads 99999999999", 2, Usage()},
      {"C10", "unknown option", B(), "run b.yaml --frobnicate", 2, Usage()},
      {"C11", "no subcommand", B(), "", 2, Usage()},
      {"C12", "--format gif", B(), "run b.yaml --format gif", 2, Usage()},
      {"C13", "--format png,png", B(), "run b.yaml --format png,png", 2, Usage()},
      {"C14", "compare with one input", B(), "compare b.yaml", 2, Usage()},
      {"C14t", "compare --tolerance negative", B(), "compare b.yaml b.yaml --no-plots --tolerance -0.1", 2, Usage()},
      {"C15", "compare with a missing second input", B(), "compare b.yaml nosuch.yaml", 2, Usage()},
      {"C16", "compare with an invalid second budget",
       With(B(), "bad.yaml", Sub(Sub(kBase, "name: cat", "name: bad"), "level: 1.0e-6", "level: -3")),
       "compare b.yaml bad.yaml --no-plots", 3, AtIn("bad.yaml", "level: |-3", "sources[0].spectrum.level")},
      {"C16e", "compare: an error only the engine finds, located in the second budget",
       With(B(), "bad.yaml", Sub(kUnstableRequired, "name: cat", "name: bad")), "compare b.yaml bad.yaml --no-plots", 3,
       AtIn("bad.yaml", "path: |plant, exact", "contributors[0].path"), {"unstable"}},
      {"C16+", "compare two budgets (valid)", With(B(), "b2.yaml", Sub(kBase, "name: cat", "name: cat2")),
       "compare b.yaml b2.yaml --no-plots", 0, Ok()},
      {"C17", "compare a directory without summary.json", B(), "compare emptydir b.yaml --no-plots", 3, Names("emptydir"),
       {}, {}, "mkdir emptydir"},
      {"C18", "compare: summary.json not JSON", With(B(), "r/summary.json", "{x\n"), "compare r b.yaml --no-plots", 3,
       Names("summary.json")},
      {"C19", "compare: summary.json of the wrong shape", With(B(), "r/summary.json", "{\"outputs\": 5}\n"),
       "compare r b.yaml --no-plots", 3, Names("summary.json")},
      {"C20", "compare: summary.json nested 100000 deep",
       With(B(), "r/summary.json", "{\"outputs\": " + std::string(100000, '[') + "\n"), "compare r b.yaml --no-plots", 3,
       Names("summary.json")},
      {"C21", "budget is /dev/null", {}, "run /dev/null --no-plots", 3, Names("/dev/null")},
      {"C22", "budget is a FIFO without a writer (D12)", {}, "run fifo.yaml --no-plots", 3, Names("fifo.yaml"),
       {kNotRegular}, {}, "mkfifo fifo.yaml", "", 20},
      {"C22c", "deb check of a FIFO budget (D12)", {}, "check fifo.yaml", 3, Names("fifo.yaml"), {kNotRegular}, {},
       "mkfifo fifo.yaml", "", 20},
      {"C23", "--out '' (the default place)", B(), "run b.yaml --no-plots --out ''", 0, Ok(), {}, {}, "", "", 0,
       CheckDefaultReport},
      {"C24", "--out / (D08)", B(), "run b.yaml --no-plots --out /", 4, Usage(), {}, {"Success"}},
      {"C25", "--out a directory of user files (D02)", kMydata, "run b.yaml --no-plots --out mydata", 4, Names("mydata"),
       {"--force"}},
      {"C25f", "--out a directory of user files --force", kMydata, "run b.yaml --no-plots --out mydata --force", 0, Ok(), {},
       {}, "", "", 0, CheckMydataReplaced},
      {"C26", "--out . (D08)", B(), "run b.yaml --no-plots --out .", 4, Usage(), {}, {"Success"}},
      {"C26r", "--out onto a report deb run wrote earlier", With(B(), "old.yaml", kOld), "run b.yaml --no-plots --out prev", 0,
       Ok(), {}, {}, EarlierReport("prev"), "", 0, CheckPrevReplaced},
      {"C36", "gnuplot missing (DEB_GNUPLOT=/nonexistent), deb run", B(), "run b.yaml", 4, Names("gnuplot"), {}, {}, "",
       "DEB_GNUPLOT=/nonexistent"},
      {"C36n", "gnuplot missing, deb run --no-plots (valid)", B(), "run b.yaml --no-plots", 0, Ok(), {}, {}, "",
       "DEB_GNUPLOT=/nonexistent", 0, CheckDefaultReport},
      {"C36c", "gnuplot missing, deb compare of two budgets (exit 4)",
       With(B(), "b2.yaml", Sub(kBase, "name: cat", "name: cat2")), "compare b.yaml b2.yaml", 4, Names("gnuplot"), {}, {},
       "", "DEB_GNUPLOT=/nonexistent"},
      {"C36w", "gnuplot missing, deb sweep (exit 4)", Budget(kSweep), "sweep b.yaml", 4, Names("gnuplot"), {}, {}, "",
       "DEB_GNUPLOT=/nonexistent"},
      {"C37", "gnuplot missing, deb spectrum convert (exit 4)", {{"spec.csv", kSpec}},
       "spectrum convert spec.csv --unit N --to N -o c.csv", 4, Names("gnuplot"), {}, {}, "", "DEB_GNUPLOT=/nonexistent"},
      {"C37b", "gnuplot missing, deb spectrum bands (exit 4)", {{"spec.csv", "# unit: um/s\n" + kSpec}},
       "spectrum bands spec.csv -o bands.csv", 4, Names("gnuplot"), {}, {}, "", "DEB_GNUPLOT=/nonexistent"},
      {"C38", "gnuplot fails (DEB_GNUPLOT=/bin/false)", B(), "run b.yaml", 4, Names("gnuplot"), {}, {}, "",
       "DEB_GNUPLOT=/bin/false"},
      {"C39", "gnuplot never exits, DEB_GNUPLOT_TIMEOUT=2 (D15)", With(B(), "hang.sh", kHang), "run b.yaml", 4,
       Names("gnuplot"), {"did not finish"}, {}, "chmod +x hang.sh", "DEB_GNUPLOT=\"$PWD/hang.sh\" DEB_GNUPLOT_TIMEOUT=2", 15},
      {"C41", "deb model on a budget without a model (valid)", B(), "model b.yaml", 0, Ok()},
      {"C42", "sweep --threads 100000 (valid)", Budget(kSweep), "sweep b.yaml --no-plots --threads 100000", 0, Ok()},
      {"C45", "compare: summary.json whose contributors is a number (D05c)", With(B(), "r/summary.json", Summary("5", "[]")),
       "compare r b.yaml --no-plots", 3, Names("summary.json")},
      {"C45+", "compare: summary.json whose contributors is a string (D05c)",
       With(B(), "r/summary.json", Summary("\"c1\"", "[]")), "compare r b.yaml --no-plots", 3, Names("summary.json")},
      {"C46", "compare: summary.json whose bands is a string (D05c)",
       With(B(), "r/summary.json", Summary(kGoodContributors, "\"decades\"")), "compare r b.yaml --no-plots", 3,
       Names("summary.json")},
      {"C46+", "compare: summary.json whose bands is a number (D05c)",
       With(B(), "r/summary.json", Summary(kGoodContributors, "7")), "compare r b.yaml --no-plots", 3,
       Names("summary.json")},
      {"C47", "compare: summary.json with variance 1e400", With(B(), "r/summary.json", Summary(kGoodContributors, "[]", "1e400")),
       "compare r b.yaml --no-plots", 3, Names("summary.json")},
      {"C48+", "compare --out onto an existing regular file (D02)",
       With(With(B(), "b2.yaml", Sub(kBase, "name: cat", "name: cat2")), "existing.txt", "keep me\n"),
       "compare b.yaml b2.yaml --no-plots --out existing.txt", 4, Names("existing.txt"),
       {"not a report written by deb", "--force"}},
      {"C49+", "compare --out a directory of user files (D02)", With(kMydata, "b2.yaml", Sub(kBase, "name: cat", "name: cat2")),
       "compare b.yaml b2.yaml --no-plots --out mydata", 4, Names("mydata"), {"--force"}},
      {"C50+", "sensitivity --out a directory of user files (D02)", kMydata,
       "sensitivity b.yaml -p 'sources[0].spectrum.level' --out mydata", 4, Names("mydata"), {"--force"}},
  };
}

// ---- X: security-minded ----------------------------------------------------
[[gnu::noinline]] std::vector<Case> SecurityCases() {
  return {
      {"X08", "reports/cat is a symlink to an earlier report elsewhere (D16)", With(B(), "old.yaml", kOld), kRun, 0, Ok(),
       {}, {}, EarlierReport("elsewhere") + " && mkdir reports && ln -s ../elsewhere reports/cat", "", 0,
       CheckSymlinkWrittenThrough},
      {"X16", "backquotes in a CSV channel name, deb spectrum bands (D01)",
       {{"spec.csv", "# unit: um/s\nf_hz,a`touch $DEBINJ`,b\n0.5,1e-6,1e-6\n1,1e-6,1e-6\n10,1e-6,1e-6\n100,1e-6,1e-6\n"}},
       "spectrum bands spec.csv -o bands.csv", 0, Ok(), {}, {}, "", "", 0, CheckInjection},
      {"X17", "backquotes in the recording's file name, deb spectrum welch (D01)", {{"a`touch $DEBINJ`.csv", RecCsv()}},
       "spectrum welch 'a`touch $DEBINJ`.csv' -o psd.csv", 0, Ok(), {}, {}, "", "", 0, CheckInjection},
      {"X17b", "backquotes in the file name, deb spectrum bands (D01)", {{"s`touch $DEBINJ`.csv", "# unit: um/s\n" + kSpec}},
       "spectrum bands 's`touch $DEBINJ`.csv' -o bands.csv", 0, Ok(), {}, {}, "", "", 0, CheckInjection},
      {"X17c", "backquotes in the file name, deb spectrum convert (D01)", {{"s`touch $DEBINJ`.csv", kSpec}},
       "spectrum convert 's`touch $DEBINJ`.csv' --unit N --to N -o c.csv", 0, Ok(), {}, {}, "", "", 0, CheckInjection},
      {"X18", "backquotes in every description of a budget, deb run with plots", Budget(kInjectionBudget), "run b.yaml", 0,
       Ok(), {}, {}, "", "", 0, CheckInjection},
      {"X19", "backquotes in source channel and path input names, deb run with plots", Budget(kInjectionChannels),
       "run b.yaml", 0, Ok(), {}, {}, "", "", 0, CheckInjection},
      {"X20", "backquotes in the input channel, deb spectrum frf (D01)", {{"rec.csv", RecFrf("F`touch $DEBINJ`,x")}},
       "spectrum frf rec.csv --input 'F`touch $DEBINJ`' --outputs x -o frf.csv", 0, Ok(), {}, {}, "", "", 0,
       CheckInjection},
      {"X20b", "backquotes in the output channel, deb spectrum frf (D01)", {{"rec.csv", RecFrf("F,x`touch $DEBINJ`")}},
       "spectrum frf rec.csv --input F --outputs 'x`touch $DEBINJ`' -o frf.csv", 0, Ok(), {}, {}, "", "", 0,
       CheckInjection},
      {"X21", "backquotes in a channel name, deb spectrum convert",
       {{"spec.csv", "f_hz,a`touch $DEBINJ`\n" + kSpecRows}}, "spectrum convert spec.csv --unit N --to N -o c.csv", 0,
       Ok(), {}, {}, "", "", 0, CheckInjection},
      {"X22", "backquotes in channel names, deb spectrum selfnoise (D01)",
       {{"rec.csv", Rec3("a`touch $DEBINJ`,b,c")}}, "spectrum selfnoise rec.csv --sensors 'a`touch $DEBINJ`,b,c' -o noise.csv",
       0, Ok(), {}, {}, "", "", 0, CheckInjection},
      {"X22w", "backquotes in channel names, deb spectrum welch --coherence (D01)",
       {{"rec.csv", Rec3("a`touch $DEBINJ`,b,c")}}, "spectrum welch rec.csv -o psd.csv --coherence coh.csv", 0, Ok(), {},
       {}, "", "", 0, CheckInjection},
  };
}

// ---- Inputs that once reached an internal check (an abort, exit 134) -------
[[gnu::noinline]] std::vector<Case> InternalCheckCases() {
  return {
      {"Y120+", "a measured reference defined only beyond the grid",
       {{"b.yaml", Reference("nm")}, {"ref.csv", "f_hz,r\n1000,1e-6\n2000,1e-6\n"}}, kRun, 3,
       At("spectrum: |{type: measured, file: ref.csv}", "outputs[0].references[0].spectrum"),
       {"reference 'r' is defined over [1000, 2000] Hz only", "does not overlap the frequency grid [1, 100] Hz"}},
      {"Y120++", "a measured reference touching the grid's end only", {{"b.yaml", Reference("nm")},
       {"ref.csv", "f_hz,r\n100,1e-6\n2000,1e-6\n"}}, kRun, 3,
       At("spectrum: |{type: measured, file: ref.csv}", "outputs[0].references[0].spectrum"), {"does not overlap"}},
      {"Y120+++", "a measured reference overlapping part of the grid (valid)",
       {{"b.yaml", Reference("nm")}, {"ref.csv", "f_hz,r\n50,1e-6\n2000,1e-6\n"}}, kRun, 0, Ok()},
      {"Y121+", "a reference PSD that overflows converted to the output's unit (um^2 -> nm^2)",
       {{"b.yaml", Reference("um")}, {"ref.csv", "f_hz,r\n0.5,1e305\n200,1e305\n"}}, kRun, 3,
       At("references: [|{name: r", "outputs[0].references[0]"), {"reference 'r' has a PSD of inf nm^2/Hz"}},
      {"C51+", "spectrum reference --points-per-decade 1e10", {},
       "spectrum reference nlnm --points-per-decade 1e10 -o r.csv", 3, Names("--points-per-decade"),
       {"from 1 to 100000"}, {}, "", "", 20},
      {"C51++", "spectrum reference --points-per-decade inf", {},
       "spectrum reference nlnm --points-per-decade inf -o r.csv", 3, Names("--points-per-decade")},
      {"C35c+", "spectrum welch --confidence 0.9999999999999999 (its upper tail rounds to 1)", {{"rec.csv", RecCsv()}},
       "spectrum welch rec.csv --bounds --confidence 0.9999999999999999 -o psd.csv", 3, Names("confidence"),
       {"too close to 1"}},
  };
}

// Every case, in the order of the sections above. One function per section:
// one initialiser of all of them took GCC three minutes to optimise (its
// points-to analysis grows faster than the function), and noinline keeps
// the sections apart.
const std::vector<Case>& Catalogue() {
  static const std::vector<Case> cases = [] {
    std::vector<Case> all;
    for (const auto& section :
         {YamlBudgetCases, ParameterCases, DelayAndSampledCases, SweepCases, SensitivityCases,
          SpectrumCsvBudgetCases, SpectrumCsvCommandCases, TimeSeriesCases, FrfTableCases, MatFileCases,
          NastranCases, Op4Cases, UncertaintyCases, OptimiseCases, UffCases, CraftedStoreCases, Mat73Cases,
          Utf8AndLimitCases, CommandLineCases, SecurityCases, InternalCheckCases}) {
      std::vector<Case> part = section();
      all.insert(all.end(), std::make_move_iterator(part.begin()), std::make_move_iterator(part.end()));
    }
    return all;
  }();
  return cases;
}

// ---------------------------------------------------------------------------
// Running a case.

std::string ShellQuote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

fs::path Root() {
  static const fs::path root = TempDir("catalogue");
  return root;
}

std::string SafeName(const std::string& id) {
  std::string s;
  for (char c : id) s += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  return s;
}

// A shell line run in `work` with stdin from /dev/null and stdout/stderr to `io`.
int Shell(const fs::path& work, const fs::path& io, const std::string& line) {
  const std::string cmd = "cd " + ShellQuote(work.string()) + " && DEB=" + ShellQuote(DEB_BINARY) +
                          " DEBINJ=" + ShellQuote((work / "INJECTED").string()) + " && export DEB DEBINJ && " + line +
                          " < /dev/null > " + ShellQuote((io / "stdout").string()) + " 2> " +
                          ShellQuote((io / "stderr").string());
  return ExitCode(std::system(cmd.c_str()));
}

// Memory bombs (a 16 GB grid) must not reach the OOM killer of a shared machine
// while deb still lacks its bounds: deb runs under a 4 GB address-space limit,
// unless deb cannot start under one (a sanitizer build reserves far more).
const std::string& MemoryLimit() {
  static const std::string limit = [] {
    const fs::path probe = Root() / "probe";
    fs::create_directories(probe);
    const std::string ulimit = "ulimit -v 4194304; ";
    const bool fits = Shell(probe, probe, ulimit + "\"$DEB\" --help") == 0;
    fs::remove_all(probe);
    return fits ? ulimit : std::string();
  }();
  return limit;
}

// Cases whose input is rejected only when the PSD is computed, so that deb
// check (which computes nothing) accepts them.
bool FoundOnlyByComputing(const std::string& id) {
  static const std::set<std::string> ids = {
      "Y35",  // a grid point on a pole of the path: found evaluating H there
      "S27",  // PSD 1e308: S_y overflows to infinity
      "F11",  // an FRF whose |H|^2 S_u overflows
      "Y121+",  // a reference whose PSD overflows in the output's unit
  };
  return ids.count(id) > 0;
}

Result RunDeb(const fs::path& work, const fs::path& io, const Case& c) {
  const std::string line =
      MemoryLimit() + (c.env.empty() ? "" : c.env + " ") + "timeout -k 5 60 \"$DEB\" " + c.args;
  const auto t0 = std::chrono::steady_clock::now();
  Result r;
  r.exit_code = Shell(work, io, line);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.out = ReadAll(io / "stdout");
  r.err = ReadAll(io / "stderr");
  return r;
}

// Every entry below `dir`: its kind, and for files size, mtime and content; for links the target.
// FIFOs are never opened; symlinks are not followed.
std::map<std::string, std::string> Snapshot(const fs::path& dir) {
  std::map<std::string, std::string> s;
  std::error_code ec;
  for (auto it = fs::recursive_directory_iterator(dir, ec); !ec && it != fs::recursive_directory_iterator();
       it.increment(ec)) {
    const fs::path p = it->path();
    const std::string rel = fs::relative(p, dir).string();
    const fs::file_status st = fs::symlink_status(p);
    if (fs::is_symlink(st)) {
      s[rel] = "link -> " + fs::read_symlink(p).string();
    } else if (fs::is_directory(st)) {
      s[rel] = "dir";
    } else if (fs::is_regular_file(st)) {
      const auto mtime = fs::last_write_time(p).time_since_epoch().count();
      s[rel] = "file " + std::to_string(fs::file_size(p)) + " bytes, mtime " + std::to_string(mtime) + ", hash " +
               std::to_string(std::hash<std::string>()(ReadAll(p)));
    } else {
      s[rel] = "special";
    }
  }
  return s;
}

std::string SnapshotDiff(const std::map<std::string, std::string>& before,
                         const std::map<std::string, std::string>& after) {
  std::string d;
  for (const auto& e : after) {
    const auto b = before.find(e.first);
    if (b == before.end()) d += "  new: " + e.first + " (" + e.second + ")\n";
    else if (b->second != e.second) d += "  changed: " + e.first + " (" + b->second + " -> " + e.second + ")\n";
  }
  for (const auto& e : before)
    if (!after.count(e.first)) d += "  deleted: " + e.first + "\n";
  return d;
}

std::string FirstErrorLine(const std::string& err) {
  std::istringstream in(err);
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("deb: error: ", 0) == 0) return line;
  return "";
}

// 1-based line and column of `marker` in `text` ('|' in the marker marks the spot).
bool MarkerPosition(const std::string& text, const std::string& marker, int* line, int* col) {
  const auto bar = marker.find('|');
  const std::string needle = bar == std::string::npos ? marker : marker.substr(0, bar) + marker.substr(bar + 1);
  const auto at = text.find(needle);
  if (at == std::string::npos) return false;
  const std::size_t spot = at + (bar == std::string::npos ? 0 : bar);
  *line = 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(spot), '\n'));
  const auto nl = text.rfind('\n', spot == 0 ? 0 : spot - 1);
  *col = static_cast<int>(nl == std::string::npos || spot == 0 ? spot + 1 : spot - nl);
  return true;
}

std::string FileContent(const Case& c, const std::string& name) {
  for (const auto& f : c.files)
    if (f.first == name) return f.second;
  return "";
}

// "" when the first error line has the expected form, else what is wrong.
std::string CheckWhere(const Case& c, const std::string& line) {
  const Where& w = c.where;
  if (w.kind == Where::kSuccess || w.kind == Where::kUsage) return "";
  if (line.empty()) return "no 'deb: error:' line";
  const std::string head = "deb: error: ";
  if (w.kind == Where::kContains)
    return line.find(w.text) == std::string::npos ? "the error line does not name '" + w.text + "'" : "";
  if (line.compare(head.size(), w.file.size(), w.file) != 0 || line.size() <= head.size() + w.file.size() ||
      line[head.size() + w.file.size()] != ':')
    return "the error line does not start with '" + w.file + ":'";
  if (w.kind == Where::kFile) return "";
  // FILE:LINE:COL: REST
  std::size_t p = head.size() + w.file.size() + 1;
  int got_line = 0, got_col = 0;
  const auto digits = [&](int* v) {
    const std::size_t s = p;
    while (p < line.size() && std::isdigit(static_cast<unsigned char>(line[p]))) *v = *v * 10 + (line[p++] - '0');
    return p > s && p < line.size() && line[p] == ':';
  };
  if (!digits(&got_line)) return "no LINE after '" + w.file + ":'";
  ++p;
  if (!digits(&got_col)) return "no COL after '" + w.file + ":LINE:'";
  p += 1;
  if (p < line.size() && line[p] == ' ') ++p;
  const std::string rest = line.substr(p);
  if (!w.marker.empty()) {
    int want_line = 0, want_col = 0;
    if (!MarkerPosition(FileContent(c, w.file), w.marker, &want_line, &want_col))
      return "catalogue bug: marker '" + w.marker + "' not in " + w.file;
    if (got_line != want_line || got_col != want_col)
      return "position " + std::to_string(got_line) + ":" + std::to_string(got_col) + ", expected " +
             std::to_string(want_line) + ":" + std::to_string(want_col) + " ('" + w.marker + "')";
  }
  if (!w.key.empty()) {
    const bool starts = rest.compare(0, w.key.size(), w.key) == 0 && rest.size() > w.key.size() &&
                        (rest[w.key.size()] == '.' || rest[w.key.size()] == '[' || rest[w.key.size()] == ':');
    if (!starts) return "the key path does not start with '" + w.key + "'";
  }
  return "";
}

// ---------------------------------------------------------------------------
// Checks of particular cases.

std::string CheckInjection(const fs::path& work, const Result&) {
  const auto injected = [&] {
    std::error_code ec;
    for (auto it = fs::recursive_directory_iterator(work, ec); !ec && it != fs::recursive_directory_iterator();
         it.increment(ec))
      if (it->path().filename() == "INJECTED") return true;
    return false;
  };
  if (injected()) return "the backquoted command ran (INJECTED exists) during the deb run";
  // The scripts deb left behind must be as harmless when someone redraws them.
  std::vector<fs::path> scripts;
  for (const auto& e : fs::recursive_directory_iterator(work))
    if (e.path().extension() == ".gp") scripts.push_back(e.path());
  if (scripts.empty()) return "no .gp script was left to re-run";
  for (const auto& gp : scripts) {
    const std::string line = "cd " + ShellQuote(gp.parent_path().string()) + " && timeout -k 5 60 gnuplot -d " +
                             ShellQuote(gp.filename().string()) + " > /dev/null 2>&1; true";
    Shell(work, work.parent_path() / "io", line);
    if (injected()) return "the backquoted command ran when gnuplot re-ran " + fs::relative(gp, work).string();
  }
  return "";
}

std::string CheckNoPasswdLine(const fs::path&, const Result& r) {
  std::istringstream in(ReadAll("/etc/passwd"));
  std::string line;
  while (std::getline(in, line))
    if (line.size() >= 8 && r.err.find(line) != std::string::npos) return "the message quotes a line of /etc/passwd";
  return "";
}

std::string CheckDefaultReport(const fs::path& work, const Result&) {
  return fs::is_regular_file(work / "reports" / "cat" / "summary.json") ? "" : "no reports/cat/summary.json";
}

double Variance(const fs::path& summary) {
  return nlohmann::json::parse(ReadAll(summary))["outputs"][0]["variance"].get<double>();
}

// `dir` holds the new report (the base level: a quarter of the earlier report's variance).
std::string CheckNewReportIn(const fs::path& work, const fs::path& dir) {
  const fs::path old = work.parent_path() / "io" / "old_summary.json";
  if (!fs::is_regular_file(dir / "summary.json")) return "no summary.json in " + dir.string();
  if (!fs::is_regular_file(old)) return "setup did not save the earlier summary.json";
  const double v_new = Variance(dir / "summary.json"), v_old = Variance(old);
  if (!(std::abs(4.0 * v_new - v_old) <= 1e-9 * v_old)) return dir.string() + " does not hold the new report";
  return "";
}

std::string CheckSymlinkWrittenThrough(const fs::path& work, const Result&) {
  if (!fs::is_symlink(work / "reports" / "cat")) return "reports/cat is no longer a symlink";
  return CheckNewReportIn(work, work / "elsewhere");
}

std::string CheckPrevReplaced(const fs::path& work, const Result&) { return CheckNewReportIn(work, work / "prev"); }

std::string CheckMydataReplaced(const fs::path& work, const Result&) {
  if (!fs::is_regular_file(work / "mydata" / "summary.json")) return "mydata/summary.json missing";
  if (fs::exists(work / "mydata" / "thesis.tex")) return "mydata still holds thesis.tex: not replaced";
  return "";
}

int DataRows(const fs::path& csv) {
  std::istringstream in(ReadAll(csv));
  std::string line;
  int rows = -1;  // the header
  while (std::getline(in, line))
    if (!line.empty() && line[0] != '#') ++rows;
  return rows;
}

std::string CheckBomRowKept(const fs::path& work, const Result&) {
  const int rows = DataRows(work / "c.csv");
  return rows == 9 ? "" : "c.csv holds " + std::to_string(rows) + " data rows, expected 9 (the BOM row was lost?)";
}

std::string CheckCrRowsRead(const fs::path& work, const Result&) {
  const int rows = DataRows(work / "c.csv");
  return rows == 9 ? "" : "c.csv holds " + std::to_string(rows) + " data rows, expected 9";
}

void WriteCaseFiles(const fs::path& work, const Files& files) {
  for (const auto& f : files) {
    const fs::path p = work / f.first;
    fs::create_directories(p.parent_path());
    std::ofstream(p, std::ios::binary).write(f.second.data(), static_cast<std::streamsize>(f.second.size()));
  }
}

std::string Excerpt(const std::string& s) { return s.size() > 600 ? s.substr(0, 600) + "..." : s; }

}  // namespace

TEST_CASE("the bad-input catalogue: each case exits as documented, located, and writes nothing when it fails") {
  // DEB_CATALOGUE=Y41,C03 runs only those cases.
  const char* only = std::getenv("DEB_CATALOGUE");
  const std::string selection = only == nullptr ? "" : "," + std::string(only) + ",";
  int ran = 0;
  std::vector<std::string> failed_ids;
  for (const Case& c : Catalogue()) {
    if (!selection.empty() && selection.find("," + c.id + ",") == std::string::npos) continue;
    CAPTURE(c.id);
    CAPTURE(c.what);
    const fs::path dir = Root() / SafeName(c.id), work = dir / "work", io = dir / "io";
    fs::create_directories(work);
    fs::create_directories(io);
    WriteCaseFiles(work, c.files);
    bool ok = true;
    if (!c.setup.empty()) {
      const int rc = Shell(work, io, "( " + c.setup + " )");
      CHECK_MESSAGE(rc == 0, "setup failed: " << c.setup << "\n" << ReadAll(io / "stderr"));
      ok = ok && rc == 0;
    }
    const auto before = Snapshot(work);
    const Result r = RunDeb(work, io, c);
    ++ran;
    const std::string line = FirstErrorLine(r.err);
    const std::string context = "deb " + c.args + "\nexit " + std::to_string(r.exit_code) + " after " +
                                std::to_string(r.seconds) + " s\nstderr: " + Excerpt(r.err);

    const bool exit_ok = r.exit_code == c.exit_code;
    CHECK_MESSAGE(exit_ok, "exit code " << r.exit_code << ", expected " << c.exit_code << "\n" << context);
    ok = ok && exit_ok;

    const std::string where = CheckWhere(c, line);
    CHECK_MESSAGE(where.empty(), where << "\nfirst error line: " << line << "\n" << context);
    ok = ok && where.empty();

    if (c.where.kind == Where::kSuccess) {
      CHECK_MESSAGE(line.empty(), "an error line on success: " << line);
      ok = ok && line.empty();
    }
    for (const auto& s : c.says) {
      const bool has = r.err.find(s) != std::string::npos;
      CHECK_MESSAGE(has, "stderr does not say '" << s << "'\n" << context);
      ok = ok && has;
    }
    for (const auto& s : c.never) {
      const bool has = r.err.find(s) != std::string::npos;
      CHECK_MESSAGE(!has, "stderr says '" << s << "'\n" << context);
      ok = ok && !has;
    }
    if (c.max_seconds > 0) {
      CHECK_MESSAGE(r.seconds <= c.max_seconds, "took " << r.seconds << " s, at most " << c.max_seconds << " s allowed");
      ok = ok && r.seconds <= c.max_seconds;
    }
    if (c.exit_code != 0) {
      const std::string diff = SnapshotDiff(before, Snapshot(work));
      CHECK_MESSAGE(diff.empty(), "the case directory changed:\n" << diff << context);
      ok = ok && diff.empty();
    }
    // What run rejects from its input, check rejects with the same first
    // line; only what is found by computing (a non-finite PSD, a pole on the
    // grid) is run's alone.
    if (c.args == kRun && c.exit_code == 3 && c.setup.empty() && !FoundOnlyByComputing(c.id)) {
      Case as_check = c;
      as_check.args = "check b.yaml";
      const Result k = RunDeb(work, io, as_check);
      const std::string check_line = FirstErrorLine(k.err);
      const bool same = k.exit_code == 3 && check_line == line;
      CHECK_MESSAGE(same, "deb check: exit " << k.exit_code << ", first error line\n  " << check_line
                                             << "\nwhere deb run says\n  " << line);
      ok = ok && same;
    }
    if (c.check != nullptr) {
      const std::string problem = c.check(work, r);
      CHECK_MESSAGE(problem.empty(), problem << "\n" << context);
      ok = ok && problem.empty();
    }
    if (ok) fs::remove_all(dir);
    else failed_ids.push_back(c.id);
  }
  std::string failed;
  for (const auto& id : failed_ids) failed += " " + id;
  const std::string summary = "bad-input catalogue: " + std::to_string(ran) + " cases ran, " +
                              std::to_string(failed_ids.size()) + " failed" + (failed.empty() ? "" : ":" + failed);
  MESSAGE(summary);
  if (selection.empty()) CHECK(ran >= 90);
  if (failed_ids.empty()) fs::remove_all(Root());
}
