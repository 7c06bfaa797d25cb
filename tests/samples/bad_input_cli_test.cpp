// SPDX-License-Identifier: MIT
// The built `odeskin` program run on a table of bad inputs, made in a scratch folder by the test:
// every case must end with its exit status (1 bad input or runtime failure, 2 usage), never a
// signal, with stderr exactly one line "odeskin: error: ..." that names the offending file or
// option, and leave the output exactly as it was (a file already there untouched, no new file, no
// temporary). Also: a write that fails part way (the file size limit standing in for a full disk),
// usage errors, and the Vulkan fault hook (ODESKIN_VK_FAULT) on play, surface, demo and render
// with --backend auto (falls back to the CPU, one note) and --backend vulkan (exit 1, one line).
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <tuple>
#include <utility>
#include <vector>

#include <csignal>
#include <fcntl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "engine/io/asset_file.hpp"
#include "engine/sanitized_build.hpp"  // tests/engine
#include "host/gpu_test_support.hpp"
#include "samples/command_test_support.hpp"

namespace odeskin {
namespace {

namespace fs = std::filesystem;

// ---- running the program -------------------------------------------------------------------------

struct Outcome {
  bool exited = false;  // false: ended by a signal (a crash or an abort)
  int status = -1;      // exit status when exited, else the signal number
  std::string out;
  std::string err;
};

std::string readText(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

void writeText(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream(path, std::ios::binary) << text;
}

struct RunOptions {
  std::map<std::string, std::string> env;  // set in the child only
  long file_size_limit = -1;               // RLIMIT_FSIZE bytes; SIGXFSZ ignored so writes fail instead
  long address_space_limit = -1;           // RLIMIT_AS bytes: allocations beyond it fail (std::bad_alloc)
  std::function<void(pid_t)> while_running;  // called with the child's pid before waiting for it
  bool stdout_unread = false;  // stdout is a pipe nobody reads, SIGPIPE ignored: writes fail (EPIPE)
};

// Runs the program with `args` (stdout and stderr captured through files in `io_dir`).
Outcome runOdeskin(const std::vector<std::string>& args, const fs::path& io_dir, const RunOptions& options = {}) {
  fs::create_directories(io_dir);
  const fs::path out_file = io_dir / "stdout.txt";
  const fs::path err_file = io_dir / "stderr.txt";
  std::vector<std::string> argv_text{ODESKIN_PROGRAM};
  argv_text.insert(argv_text.end(), args.begin(), args.end());
  std::vector<char*> argv;
  argv.reserve(argv_text.size() + 1);
  for (std::string& a : argv_text) argv.push_back(a.data());
  argv.push_back(nullptr);
  // The child's environment is built here, before fork: between fork and exec only async-signal-safe
  // calls are allowed, and setenv is not one (it allocates, and another thread may hold malloc's lock).
  std::vector<std::string> env_text;
  for (char** e = environ; *e != nullptr; ++e) {
    const std::string entry(*e);
    if (!options.env.contains(entry.substr(0, entry.find('=')))) env_text.push_back(entry);
  }
  for (const auto& [name, value] : options.env) env_text.push_back(name + "=" + value);
  std::vector<char*> envp;
  envp.reserve(env_text.size() + 1);
  for (std::string& e : env_text) envp.push_back(e.data());
  envp.push_back(nullptr);

  const pid_t pid = ::fork();
  if (pid == 0) {
    const int out_fd = ::open(out_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int err_fd = ::open(err_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (out_fd < 0 || err_fd < 0) ::_exit(126);
    ::dup2(out_fd, STDOUT_FILENO);
    ::dup2(err_fd, STDERR_FILENO);
    if (options.stdout_unread) {
      int ends[2];
      if (::pipe(ends) != 0) ::_exit(126);
      ::close(ends[0]);
      ::dup2(ends[1], STDOUT_FILENO);
      std::signal(SIGPIPE, SIG_IGN);  // inherited through exec
    }
    if (options.file_size_limit >= 0) {
      std::signal(SIGXFSZ, SIG_IGN);  // inherited through exec: write() fails with EFBIG instead
      const rlimit limit{static_cast<rlim_t>(options.file_size_limit), static_cast<rlim_t>(options.file_size_limit)};
      ::setrlimit(RLIMIT_FSIZE, &limit);
    }
    if (options.address_space_limit >= 0) {
      const rlimit limit{static_cast<rlim_t>(options.address_space_limit),
                         static_cast<rlim_t>(options.address_space_limit)};
      ::setrlimit(RLIMIT_AS, &limit);
    }
    ::execve(argv[0], argv.data(), envp.data());
    ::_exit(127);
  }
  Outcome outcome;
  if (pid > 0 && options.while_running) options.while_running(pid);
  int wstatus = 0;
  if (pid < 0 || ::waitpid(pid, &wstatus, 0) != pid) {
    ADD_FAILURE() << "cannot run " << ODESKIN_PROGRAM;
    return outcome;
  }
  outcome.exited = WIFEXITED(wstatus);
  outcome.status = outcome.exited ? WEXITSTATUS(wstatus) : WTERMSIG(wstatus);
  outcome.out = readText(out_file);
  outcome.err = readText(err_file);
  return outcome;
}

std::string commandLine(const std::vector<std::string>& args) {
  std::string line = "odeskin";
  for (const std::string& a : args) line += " " + a;
  return line;
}

// Exit `status`, stderr one line "odeskin: error: ..." containing every part of `parts`.
void expectOneErrorLine(const Outcome& r, int status, const std::vector<std::string>& parts, const std::string& what) {
  ASSERT_TRUE(r.exited) << what << ": ended by signal " << r.status << "\nstderr: " << r.err;
  EXPECT_EQ(r.status, status) << what << "\nstderr: " << r.err;
  EXPECT_EQ(r.err.rfind("odeskin: error: ", 0), 0u) << what << "\nstderr: " << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << what << "\nstderr: " << r.err;
  EXPECT_EQ(r.err.back(), '\n') << what;
  for (const std::string& part : parts) EXPECT_NE(r.err.find(part), std::string::npos) << what << "\nstderr: " << r.err;
}

// Every file under `dir`, relative, with its content.
std::map<std::string, std::string> snapshot(const fs::path& dir) {
  std::map<std::string, std::string> files;
  if (!fs::exists(dir)) return files;
  for (const fs::directory_entry& e : fs::recursive_directory_iterator(dir)) {
    files[fs::relative(e.path(), dir).string()] = e.is_regular_file() ? readText(e.path()) : "<dir>";
  }
  return files;
}

// ---- the inputs ------------------------------------------------------------------------------------

const fs::path kCylinder = fs::path(ODESKIN_DATA_DIR) / "cylinder";

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

std::string joined(const std::vector<std::string>& ls) {
  std::string text;
  for (const std::string& l : ls) text += l + "\n";
  return text;
}

// `obj` with its first line starting with `prefix` replaced by `line` (or `line` appended).
std::string replaceFirst(const std::string& obj, const std::string& prefix, const std::string& line) {
  std::vector<std::string> ls = lines(obj);
  for (std::string& l : ls) {
    if (l.rfind(prefix, 0) == 0) {
      l = line;
      return joined(ls);
    }
  }
  ls.push_back(line);
  return joined(ls);
}

std::uint64_t readU64(const std::string& bytes, std::size_t at) {
  std::uint64_t x = 0;
  for (int i = 7; i >= 0; --i) x = (x << 8) | static_cast<unsigned char>(bytes[at + static_cast<std::size_t>(i)]);
  return x;
}

void writeU64(std::string& bytes, std::size_t at, std::uint64_t x) {
  for (int i = 0; i < 8; ++i) bytes[at + static_cast<std::size_t>(i)] = static_cast<char>((x >> (8 * i)) & 0xFFu);
}

// A consistent .odsk (checksum recomputed) whose REST section claims 2^60 positions: the reader
// must refuse it before allocating.
std::string hugeRestCount(std::string bytes) {
  constexpr std::size_t kHeader = 32;
  std::size_t pos = kHeader;
  while (pos + 12 <= bytes.size()) {
    const std::string tag = bytes.substr(pos, 4);
    const std::uint64_t size = readU64(bytes, pos + 4);
    if (tag == "REST") writeU64(bytes, pos + 12, std::uint64_t{1} << 60);
    pos += 12 + static_cast<std::size_t>(size);
  }
  writeU64(bytes, 24, assetChecksum(std::string_view(bytes).substr(kHeader)));
  return bytes;
}

// A four-vertex glTF (a tetrahedron) with its buffer beside it; `edit` changes the JSON.
void writeGltf(const fs::path& path, const std::function<void(nlohmann::json&)>& edit) {
  std::string bin;
  const float positions[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  const std::uint16_t indices[12] = {0, 1, 2, 0, 2, 3, 0, 3, 1, 1, 3, 2};
  bin.append(reinterpret_cast<const char*>(positions), sizeof positions);
  bin.append(reinterpret_cast<const char*>(indices), sizeof indices);
  writeText(path.parent_path() / (path.stem().string() + ".bin"), bin);
  nlohmann::json doc = {
      {"asset", {{"version", "2.0"}}},
      {"buffers", {{{"uri", path.stem().string() + ".bin"}, {"byteLength", bin.size()}}}},
      {"bufferViews",
       {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 48}}, {{"buffer", 0}, {"byteOffset", 48}, {"byteLength", 24}}}},
      {"accessors",
       {{{"bufferView", 0}, {"componentType", 5126}, {"count", 4}, {"type", "VEC3"}, {"min", {0, 0, 0}}, {"max", {1, 1, 1}}},
        {{"bufferView", 1}, {"componentType", 5123}, {"count", 12}, {"type", "SCALAR"}}}},
      {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}}}, {"indices", 1}}}}}}},
      {"nodes", {{{"mesh", 0}}}},
      {"scenes", {{{"nodes", {0}}}}},
      {"scene", 0}};
  edit(doc);
  writeText(path, doc.dump());
}

// The scratch folder with every input, and a cylinder asset fitted by the program itself.
class BadInputCli : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new fs::path(testing::scratchDir("odeskin_bad_input_cli_", "inputs"));
    const fs::path& d = *dir_;
    const std::string pose1 = readText(kCylinder / "poses-1" / "cylinder-1.obj");
    const std::string pose2 = readText(kCylinder / "poses-1" / "cylinder-2.obj");
    writeText(d / "good1.obj", pose1);
    writeText(d / "good2.obj", pose2);
    writeText(d / "good3.obj", readText(kCylinder / "poses-1" / "cylinder-3.obj"));
    writeText(d / "empty.obj", "");
    writeText(d / "nan.obj", replaceFirst(pose2, "v ", "v nan 0 0"));
    writeText(d / "inf.obj", replaceFirst(pose2, "v ", "v 0 inf 0"));
    // Finite, but 1e200 times the cylinder: squared lengths overflow (the rig and the plane cuts
    // crashed on it); 1e-200 times: they underflow. Moved 1e308 along x: its centroids' sums
    // overflow (the rig ran out of memory following NaN distances).
    for (const auto& [name, scale, shift] :
         {std::tuple{"huge.obj", 1e200, 0.0}, std::tuple{"tiny.obj", 1e-200, 0.0}, std::tuple{"far.obj", 1.0, 1e308}}) {
      std::vector<std::string> ls = lines(pose2);
      for (std::string& l : ls) {
        if (l.rfind("v ", 0) != 0) continue;
        std::istringstream in(l.substr(2));
        double x = 0.0, y = 0.0, z = 0.0;
        in >> x >> y >> z;
        std::ostringstream out;
        out << "v " << x * scale + shift << " " << y * scale << " " << z * scale;
        l = out.str();
      }
      writeText(d / name, joined(ls));
    }
    writeText(d / "tet.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 3 4\nf 1 4 2\nf 2 4 3\n");
    // Same vertices, the first face's corners rotated: the face lists differ.
    {
      std::vector<std::string> ls = lines(pose2);
      for (std::string& l : ls) {
        if (l.rfind("f ", 0) != 0) continue;
        std::istringstream in(l.substr(2));
        std::string a, b, c;
        in >> a >> b >> c;
        l = "f " + b + " " + c + " " + a;
        break;
      }
      writeText(d / "faces_rotated.obj", joined(ls));
    }
    writeText(d / "degenerate1.obj", replaceFirst(pose1, "f ", "f 1 1 2"));
    writeText(d / "degenerate2.obj", replaceFirst(pose2, "f ", "f 1 1 2"));
    writeText(d / "bad_index.obj", replaceFirst(pose2, "f ", "f 1 2 99999"));
    writeText(d / "unbound.obj", pose2 + "v 5 5 5\n");
    writeText(d / "unbound1.obj", pose1 + "v 5 5 5\n");
    // A third face on the edge 1-2 of the first face: non-manifold in every pose.
    writeText(d / "nonmanifold1.obj", pose1 + "v 9 9 9\nf 1 2 421\n");
    writeText(d / "nonmanifold2.obj", pose2 + "v 9 9 9\nf 1 2 421\n");
    {
      std::vector<std::string> ls = lines(pose2);
      for (std::string& l : ls) {
        if (l.rfind("v ", 0) == 0) l = "v 0 0 0";
      }
      writeText(d / "collapsed.obj", joined(ls));
    }

    // Weights (libigl .dmat: "cols rows", then column-major values) from the cylinder's.
    const std::vector<std::string> dmat = lines(readText(kCylinder / "cylinder.DMAT"));
    std::vector<std::string> doubled{dmat[0]};
    for (std::size_t i = 1; i < dmat.size(); ++i) doubled.push_back(std::to_string(2.0 * std::stod(dmat[i])));
    writeText(d / "sum_two.dmat", joined(doubled));
    std::vector<std::string> extra = dmat;
    extra[0] = "5 420";
    for (int i = 0; i < 420; ++i) extra.push_back("0");
    writeText(d / "extra_bone.dmat", joined(extra));
    writeText(d / "huge.dmat", "4 99999999999\n1\n2\n3\n");
    std::vector<std::string> nan_weight = dmat;
    nan_weight[3] = "nan";
    writeText(d / "nan_weight.dmat", joined(nan_weight));
    std::vector<std::string> negative = dmat;
    negative[3] = "-0.5";
    writeText(d / "negative.dmat", joined(negative));

    // glTF: good, and with a missing / mistyped / oversized accessor.
    writeGltf(d / "tet.gltf", [](nlohmann::json&) {});
    writeGltf(d / "missing_accessor.gltf", [](nlohmann::json& j) {
      j["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = 7;
    });
    writeGltf(d / "no_position.gltf",
              [](nlohmann::json& j) { j["meshes"][0]["primitives"][0]["attributes"].erase("POSITION"); });
    writeGltf(d / "mistyped.gltf", [](nlohmann::json& j) { j["accessors"][0]["type"] = "VEC2"; });
    writeGltf(d / "mistyped_component.gltf", [](nlohmann::json& j) { j["accessors"][0]["componentType"] = 5123; });
    writeGltf(d / "huge_count.gltf", [](nlohmann::json& j) { j["accessors"][0]["count"] = 4000000000u; });
    writeGltf(d / "huge_buffer.gltf", [](nlohmann::json& j) { j["buffers"][0]["byteLength"] = 1000000000000000ull; });
    writeGltf(d / "cut.gltf", [](nlohmann::json&) {});
    writeText(d / "cut.gltf", readText(d / "cut.gltf").substr(0, 200));

    // Surface networks.
    const fs::path networks = fs::path(ODESKIN_SOURCE_DIR) / "samples" / "surfaces" / "networks";
    const std::string patch = readText(networks / "patch.json");
    writeText(d / "patch.json", patch);
    std::string columns = patch;
    columns.replace(columns.find("\"columns\": 1,"), 13, "\"columns\": 1000000000,");
    writeText(d / "huge_columns.json", columns);
    writeText(d / "cut.json", patch.substr(0, patch.size() / 2));

    // The asset, fitted by the program (a success case in its own right).
    const Outcome fit = runOdeskin({"fit", (d / "good1.obj").string(), (d / "good2.obj").string(), "--bind",
                                    (kCylinder / "cylinder.obj").string(), "--rig", (kCylinder / "cylinder.tgf").string(),
                                    "--weights", (kCylinder / "cylinder.DMAT").string(), "-q", "-o",
                                    (d / "cyl.odsk").string()},
                                   d / "io" / "setup");
    ASSERT_TRUE(fit.exited && fit.status == 0) << fit.err;
    const std::string asset = readText(d / "cyl.odsk");
    writeText(d / "truncated.odsk", asset.substr(0, asset.size() / 2));
    std::string flipped = asset;
    flipped[flipped.size() / 2] = static_cast<char>(flipped[flipped.size() / 2] ^ 0x10);
    writeText(d / "flipped.odsk", flipped);
    writeText(d / "huge_rest.odsk", hugeRestCount(asset));
    writeText(d / "not_an_asset.odsk", pose1);
  }
  static void TearDownTestSuite() {
    fs::remove_all(*dir_);
    delete dir_;
  }
  static std::string in(const std::string& name) { return (*dir_ / name).string(); }
  static fs::path dir() { return *dir_; }

  static fs::path* dir_;
};
fs::path* BadInputCli::dir_ = nullptr;

// One row: the arguments ("{out}" becomes the case's output path, which holds a file already),
// the exit status, and the parts the error line must contain (the file first).
struct BadCase {
  std::string name;
  std::vector<std::string> args;
  std::string output;  // file name of the output, created beforehand with known content
  int status;
  std::vector<std::string> parts;
};

void runTable(const std::vector<BadCase>& cases, const fs::path& root) {
  for (const BadCase& c : cases) {
    const fs::path out_dir = root / c.name;
    const fs::path output = out_dir / c.output;
    writeText(output, "precious: written before the command ran\n");
    const std::map<std::string, std::string> before = snapshot(out_dir);
    std::vector<std::string> args = c.args;
    for (std::string& a : args) {
      if (const std::size_t at = a.find("{out}"); at != std::string::npos) a.replace(at, 5, output.string());
    }
    const Outcome r = runOdeskin(args, root / "io" / c.name);
    expectOneErrorLine(r, c.status, c.parts, c.name + ": " + commandLine(args));
    EXPECT_EQ(snapshot(out_dir), before) << c.name << ": the output folder changed";
  }
}

TEST_F(BadInputCli, BadMeshesPosesAndWeightsFailNamingTheFile) {
  const std::string w = "--weights", rig = (kCylinder / "cylinder.tgf").string(), bind = (kCylinder / "cylinder.obj").string();
  auto fitWeights = [&](const std::string& weights) {
    return std::vector<std::string>{"fit", in("good1.obj"), in("good2.obj"), "--bind", bind, "--rig", rig, w, in(weights),
                                    "-o", "{out}"};
  };
  const std::vector<BadCase> cases{
      {"fit_vertex_count", {"fit", in("good1.obj"), in("tet.obj"), "-o", "{out}"}, "x.odsk", 1,
       {"tet.obj: 4 vertices but ", "good1.obj has 420"}},
      {"fit_face_list", {"fit", in("good1.obj"), in("faces_rotated.obj"), "-o", "{out}"}, "x.odsk", 1,
       {"faces_rotated.obj: face 1 is "}},
      {"fit_empty", {"fit", in("good1.obj"), in("empty.obj"), "-o", "{out}"}, "x.odsk", 1, {"empty.obj: no vertices"}},
      {"fit_nan", {"fit", in("good1.obj"), in("nan.obj"), "-o", "{out}"}, "x.odsk", 1,
       {"nan.obj:", "vertex needs 3 finite coordinates"}},
      {"fit_inf", {"fit", in("good1.obj"), in("inf.obj"), "-o", "{out}"}, "x.odsk", 1,
       {"inf.obj:", "vertex needs 3 finite coordinates"}},
      {"fit_huge", {"fit", in("good1.obj"), in("huge.obj"), "-o", "{out}"}, "x.odsk", 1,
       {"huge.obj: the mesh is too large for double-precision distances"}},
      {"fit_huge_given_rig", {"fit", in("huge.obj"), in("huge.obj"), "--bind", in("huge.obj"), "--rig", rig, w, (kCylinder / "cylinder.DMAT").string(),
                              "-o", "{out}"},
       "x.odsk", 1, {"huge.obj: the mesh is too large for double-precision distances"}},
      {"fit_degenerate_face", {"fit", in("degenerate1.obj"), in("degenerate2.obj"), "-o", "{out}"}, "x.odsk", 1,
       {"degenerate1.obj: face 1 repeats a vertex"}},
      {"fit_nonmanifold", {"fit", in("nonmanifold1.obj"), in("nonmanifold2.obj"), "-o", "{out}"}, "x.odsk", 1,
       {"nonmanifold1.obj: face 801 makes the mesh non-manifold"}},
      {"fit_face_index", {"fit", in("good1.obj"), in("bad_index.obj"), "-o", "{out}"}, "x.odsk", 1,
       {"bad_index.obj:", "face index 99999"}},
      {"fit_unbound_vertex", {"fit", in("good1.obj"), in("unbound.obj"), "-o", "{out}"}, "x.odsk", 1,
       {"unbound.obj: 421 vertices but "}},
      {"fit_collapsed", {"fit", in("good1.obj"), in("collapsed.obj"), "-o", "{out}"}, "x.odsk", 1,
       {"fit: ", "good1.obj, ", "collapsed.obj: auto rig: the mesh", "collinear"}},
      {"fit_weights_sum", fitWeights("sum_two.dmat"), "x.odsk", 1, {"sum_two.dmat: weights of vertex 0 sum to 2"}},
      {"fit_weights_bone_out_of_range", fitWeights("extra_bone.dmat"), "x.odsk", 1,
       {"extra_bone.dmat: weights are 420 x 5, expected 420 vertices x 4 bones"}},
      {"fit_weights_huge", fitWeights("huge.dmat"), "x.odsk", 1, {"huge.dmat: header says 4 columns x 99999999999 rows"}},
      {"fit_weights_nan", fitWeights("nan_weight.dmat"), "x.odsk", 1, {"nan_weight.dmat:", "not a finite number"}},
      {"fit_weights_negative", fitWeights("negative.dmat"), "x.odsk", 1, {"negative.dmat: vertex", "< 0"}},
      {"fit_resonant_material",
       {"fit", in("good1.obj"), in("good2.obj"), "--material", "1,-10,46.957190843732,0", "-o", "{out}"}, "x.odsk", 1,
       {"fit: --material '1,-10,46.957190843732,0': mode 0", "resonant"}},
      {"fit_degenerate_material", {"fit", in("good1.obj"), in("good2.obj"), "--material", "0,0,0,0", "-o", "{out}"},
       "x.odsk", 1, {"fit: --material '0,0,0,0': mode 0", "rho = eta = h = 0"}},
      {"fit_missing_pose", {"fit", in("good1.obj"), in("absent.obj"), "-o", "{out}"}, "x.odsk", 1, {"absent.obj"}},
      {"evaluate_vertex_count", {"evaluate", in("good1.obj"), in("tet.obj"), in("good2.obj"), "--keys", "0,2", "--json", "{out}"},
       "x.json", 1, {"tet.obj: 4 vertices but "}},
      {"evaluate_nan", {"evaluate", in("good1.obj"), in("nan.obj"), in("good2.obj"), "--keys", "0,2", "--json", "{out}"},
       "x.json", 1, {"nan.obj:", "finite"}},
      {"rig_empty", {"rig", in("empty.obj"), "-o", "{out}"}, "x.tgf", 1, {"rig: ", "empty.obj: no vertices"}},
      {"rig_nonmanifold", {"rig", in("nonmanifold1.obj"), "-o", "{out}"}, "x.tgf", 1,
       {"rig: ", "nonmanifold1.obj: face 801 makes the mesh non-manifold"}},
      {"rig_nan", {"rig", in("nan.obj"), "-o", "{out}"}, "x.tgf", 1, {"rig: ", "nan.obj:", "finite"}},
      {"rig_collapsed", {"rig", in("collapsed.obj"), "-o", "{out}"}, "x.tgf", 1, {"rig: ", "collapsed.obj: curve skeleton: ", "length 0"}},
      {"rig_huge", {"rig", in("huge.obj"), "-o", "{out}"}, "x.tgf", 1,
       {"rig: ", "huge.obj: curve skeleton: the mesh is too large for double-precision distances", "scale it down"}},
      {"rig_tiny", {"rig", in("tiny.obj"), "-o", "{out}"}, "x.tgf", 1,
       {"rig: ", "tiny.obj: curve skeleton: the mesh is too small for double-precision distances", "scale it up"}},
      {"rig_far", {"rig", in("far.obj"), "-o", "{out}"}, "x.tgf", 1,
       {"rig: ", "far.obj: curve skeleton: the mesh lies too far from the origin for double-precision sums",
        "move it towards the origin"}},
      {"fit_far", {"fit", in("good1.obj"), in("far.obj"), "-o", "{out}"}, "x.odsk", 1,
       {"far.obj: the mesh lies too far from the origin for double-precision sums"}},
      {"fit_tiny", {"fit", in("good1.obj"), in("tiny.obj"), "-o", "{out}"}, "x.odsk", 1,
       {"tiny.obj: the mesh is too small for double-precision distances"}},
      {"reconstruct_empty", {"reconstruct", in("empty.obj"), "-o", "{out}"}, "x.obj", 1, {"empty.obj: no vertices"}},
      {"reconstruct_nonmanifold", {"reconstruct", in("nonmanifold2.obj"), "-o", "{out}"}, "x.obj", 1,
       {"nonmanifold2.obj: edge", "not manifold"}},
      {"reconstruct_unbound", {"reconstruct", in("unbound1.obj"), "-o", "{out}"}, "x.obj", 1,
       {"unbound1.obj: vertex 421 is in no face"}},
      {"render_empty", {"render", in("empty.obj"), "-o", "{out}"}, "x.png", 1, {"empty.obj: no vertices"}},
      {"render_nan", {"render", in("nan.obj"), "-o", "{out}"}, "x.png", 1, {"nan.obj:", "finite"}},
      {"compare_nan", {"compare", in("nan.obj"), in("good1.obj"), "-o", "{out}"}, "x.ply", 1, {"nan.obj:", "finite"}},
  };
  runTable(cases, dir() / "meshes");
}

TEST_F(BadInputCli, DamagedAssetsFailOnEveryVerbThatReadsThem) {
  std::vector<BadCase> cases;
  const std::vector<std::pair<std::string, std::string>> assets{
      {"truncated.odsk", "truncated or padded"},
      {"flipped.odsk", "checksum mismatch"},
      {"huge_rest.odsk", "'REST'"},
      {"not_an_asset.odsk", "not an odeskin asset"}};
  for (const auto& [file, problem] : assets) {
    const std::string stem = fs::path(file).stem().string();
    cases.push_back({"play_" + stem, {"play", in(file), "--t", "0.5", "-o", "{out}"}, "x.obj", 1, {file + ": ", problem}});
    cases.push_back({"export_" + stem, {"export", in(file), "-o", "{out}"}, "x.glb", 1, {file + ": ", problem}});
    cases.push_back({"info_" + stem, {"info", in(file)}, "untouched.txt", 1, {file + ": ", problem}});
    cases.push_back({"render_" + stem, {"render", in(file), "-o", "{out}"}, "x.png", 1, {file + ": ", problem}});
    cases.push_back({"compare_" + stem, {"compare", in("good1.obj"), in(file), "-o", "{out}"}, "x.ply", 1,
                     {file + ": ", problem}});
  }
  runTable(cases, dir() / "assets");
}

TEST_F(BadInputCli, MalformedGltfAndNetworksAreRefusedBeforeAllocating) {
  const std::vector<BadCase> cases{
      {"gltf_missing_accessor", {"render", in("missing_accessor.gltf"), "-o", "{out}"}, "x.png", 1,
       {"missing_accessor.gltf: accessor 7", "does not exist"}},
      {"gltf_no_position", {"render", in("no_position.gltf"), "-o", "{out}"}, "x.png", 1,
       {"no_position.gltf: mesh 0 primitive 0 has no POSITION"}},
      {"gltf_mistyped", {"render", in("mistyped.gltf"), "-o", "{out}"}, "x.png", 1,
       {"mistyped.gltf: accessor 0", "type VEC2, expected VEC3"}},
      {"gltf_mistyped_component", {"render", in("mistyped_component.gltf"), "-o", "{out}"}, "x.png", 1,
       {"mistyped_component.gltf: accessor 0", "component type"}},
      {"gltf_huge_count", {"render", in("huge_count.gltf"), "-o", "{out}"}, "x.png", 1,
       {"huge_count.gltf: accessor 0", "run past the end of bufferView 0"}},
      {"gltf_huge_buffer", {"fit", in("huge_buffer.gltf"), "--times", "0,1", "-o", "{out}"}, "x.odsk", 1,
       {"huge_buffer.gltf: "}},
      {"gltf_cut", {"fit", in("cut.gltf"), "--times", "0,1", "-o", "{out}"}, "x.odsk", 1, {"cut.gltf: ", "parse error"}},
      {"gltf_unskinned_times", {"fit", in("tet.gltf"), "--times", "0,1", "-o", "{out}"}, "x.odsk", 1,
       {"tet.gltf: poses at times need an animation, and the file has none"}},
      {"surface_huge_columns", {"surface", in("huge_columns.json"), "-o", "{out}"}, "x.glb", 1,
       {"huge_columns.json: columns: expected an integer in [1, 16777216]"}},
      {"surface_huge_grid", {"surface", in("patch.json"), "--res", "100000,100000", "-o", "{out}"}, "x.glb", 1,
       {"patch.json: tessellation: 100000 x 100000 vertices exceed the limit"}},
      {"surface_cut_json", {"surface", in("cut.json"), "-o", "{out}"}, "x.glb", 1, {"cut.json"}},
      {"blend_resonant",
       {"blend", "--example", "3.16", "--beta", "39.47841760435743", "--gamma", "0", "-o", "{out}"}, "x.obj", 1,
       {"blend: ", "resonant"}},
      {"blend_alpha_zero", {"blend", "--example", "3.16", "--alpha", "0", "-o", "{out}"}, "x.obj", 1,
       {"blend: ", "alpha = 0"}},
  };
  runTable(cases, dir() / "formats");
}

TEST_F(BadInputCli, UsageErrorsExitTwoWithOneLine) {
  const std::vector<BadCase> cases{
      {"terms_zero", {"fit", in("good1.obj"), in("good2.obj"), "--terms", "0", "-o", "{out}"}, "x.odsk", 2,
       {"--terms", "(see odeskin fit --help)"}},
      {"terms_huge", {"fit", in("good1.obj"), in("good2.obj"), "--terms", "1000", "-o", "{out}"}, "x.odsk", 2,
       {"--terms", "1000"}},
      {"terms_hex", {"fit", in("good1.obj"), in("good2.obj"), "--terms", "0x10", "-o", "{out}"}, "x.odsk", 2,
       {"--terms: Value 0x10 is not a decimal integer"}},
      {"keys_binary", {"evaluate", in("good1.obj"), in("good2.obj"), "--keys", "0,0b1", "--json", "{out}"}, "x.json", 2,
       {"--keys: Value 0b1 is not a decimal integer"}},
      {"material_nan", {"fit", in("good1.obj"), in("good2.obj"), "--material", "nan,1,1,1", "-o", "{out}"}, "x.odsk", 2,
       {"--material", "'nan' is not a finite number"}},
      {"play_time_outside", {"play", in("cyl.odsk"), "--t", "7", "-o", "{out}"}, "x.obj", 2,
       {"--t 7 is outside [0, 1]", "cyl.odsk"}},
      {"play_too_many_frames", {"play", in("cyl.odsk"), "--fps", "1000", "--seconds", "100000", "-o", "{out}_%04d.obj"},
       "x.obj", 2, {"frames"}},
      {"play_size_without_png", {"play", in("cyl.odsk"), "--t", "0.5", "--size", "1x1", "-o", "{out}"}, "x.obj", 2,
       {"--size requires --png"}},
      {"rig_azimuth_without_png", {"rig", in("good1.obj"), "--azimuth", "40", "-o", "{out}"}, "x.tgf", 2,
       {"--azimuth requires --png"}},
      {"fit_output_not_odsk", {"fit", in("good1.obj"), in("good2.obj"), "-o", "{out}"}, "x.obj", 2,
       {"the asset is written as .odsk"}},
      {"export_interpolation", {"export", in("cyl.odsk"), "--interpolation", "bezier", "-o", "{out}"}, "x.glb", 2,
       {"--interpolation must be cubic or linear, got 'bezier'"}},
      {"play_pc2_too_big", {"play", in("cyl.odsk"), "--fps", "1000", "--seconds", "999", "-o", "{out}"}, "x.pc2", 2,
       {"x.pc2: 999001 frames of", "over the 4 GiB one point cache holds"}},
      {"missing_option", {"fit", in("good1.obj"), in("good2.obj")}, "x.odsk", 2, {"--output is required"}},
      {"unknown_option", {"play", in("cyl.odsk"), "--bogus"}, "x.obj", 2, {"--bogus", "(see odeskin play --help)"}},
      {"unknown_verb", {"nosuchverb", in("cyl.odsk")}, "x.obj", 2, {"unknown command 'nosuchverb'"}},
      {"no_verb", {}, "x.obj", 2, {"(see odeskin --help)"}},
      {"render_size", {"render", in("good1.obj"), "--size", "100000x100000", "-o", "{out}"}, "x.png", 2,
       {"--size '100000x100000'"}},
      {"blend_grid", {"blend", "--example", "3.17", "--res", "100000,100000", "-o", "{out}"}, "x.obj", 2,
       {"--res 100000,100000"}},
      {"rig_azimuth", {"rig", in("good1.obj"), "--png", "x.png", "--azimuth", "nan", "-o", "{out}"}, "x.tgf", 2,
       {"rig: --azimuth must be a finite number of degrees, got nan"}},
      {"rig_repeat_huge", {"rig", in("good1.obj"), "--repeat", "100000000", "-o", "{out}"}, "x.tgf", 2,
       {"rig: --repeat must lie in [1, 100000], got 100000000"}},
      {"reconstruct_samples", {"reconstruct", in("good1.obj"), "--rows", "1000", "--cols", "1000", "--points", "1000",
                               "-o", "{out}"}, "x.obj", 2, {"--rows 1000 --cols 1000 --points 1000"}},
  };
  runTable(cases, dir() / "usage");
}

// An output that names an input, directly, spelt another way, or through a symbolic link, is
// refused before anything is read: `fit a.obj b.obj -o a.obj` once wrote the asset over a.obj.
TEST_F(BadInputCli, OutputsThatWouldReplaceAnInputAreRefused) {
  const fs::path c = dir() / "replace";
  fs::create_directories(c);
  fs::copy_file(in("good1.obj"), c / "pose1.obj", fs::copy_options::overwrite_existing);
  fs::copy_file(in("good2.obj"), c / "pose2.obj", fs::copy_options::overwrite_existing);
  fs::copy_file(kCylinder / "cylinder.tgf", c / "truth.tgf", fs::copy_options::overwrite_existing);
  fs::copy_file(in("cyl.odsk"), c / "asset.odsk", fs::copy_options::overwrite_existing);
  fs::copy_file(in("cyl.odsk"), c / "frame1.obj", fs::copy_options::overwrite_existing);
  fs::copy_file(in("patch.json"), c / "patch.obj", fs::copy_options::overwrite_existing);
  for (const char* link : {"alias.obj", "alias.png", "asset_alias.obj", "asset_alias.glb"}) fs::remove(c / link);
  fs::create_symlink("pose1.obj", c / "alias.png");
  fs::create_symlink("pose1.obj", c / "alias.obj");
  fs::create_symlink("asset.odsk", c / "asset_alias.obj");
  fs::create_symlink("asset.odsk", c / "asset_alias.glb");
  const std::string pose1 = (c / "pose1.obj").string();
  const std::string pose2 = (c / "pose2.obj").string();
  const std::string asset = (c / "asset.odsk").string();
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases{
      {{"fit", pose1, pose2, "-o", pose1}, "pose1.obj is an input; it would be overwritten"},
      {{"fit", pose1, (c / "." / "pose2.obj").string(), "-o", pose2}, "pose2.obj is an input"},
      {{"fit", pose1, pose2, "-o", (c / "alias.obj").string()}, "alias.obj is an input"},
      {{"rig", pose1, "-o", (c / "truth.tgf").string(), "--compare", (c / "truth.tgf").string()}, "truth.tgf is an input"},
      {{"reconstruct", pose1, "-o", (c / "alias.obj").string()}, "alias.obj is an input"},
      {{"evaluate", pose1, pose2, in("good3.obj"), "--keys", "0,2", "--json", pose2}, "pose2.obj is an input"},
      {{"play", asset, "--t", "1", "-o", (c / "asset_alias.obj").string()}, "asset_alias.obj is an input"},
      {{"play", (c / "frame1.obj").string(), "--fps", "2", "-o", (c / "frame%d.obj").string()}, "frame1.obj is an input"},
      {{"play", asset, "--fps", "2", "-o", (c / "out.glb").string(), "--materials", (c / "out.glb").string()},
       "out.glb is an input"},
      {{"export", asset, "-o", (c / "asset_alias.glb").string()}, "asset_alias.glb is an input"},
      {{"render", pose1, "-o", (c / "alias.png").string()}, "alias.png is an input"},
      {{"surface", (c / "patch.obj").string(), "-o", (c / "patch.glb").string(), "--obj"}, "patch.obj is an input"},
  };
  const std::string pose1_before = readText(c / "pose1.obj");
  const std::string pose2_before = readText(c / "pose2.obj");
  const std::string truth_before = readText(c / "truth.tgf");
  const std::string asset_before = readText(c / "asset.odsk");
  const std::string frame1_before = readText(c / "frame1.obj");
  const std::string patch_before = readText(c / "patch.obj");
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const Outcome r = runOdeskin(cases[i].first, dir() / "io" / ("replace" + std::to_string(i)));
    expectOneErrorLine(r, 2, {cases[i].second}, commandLine(cases[i].first));
  }
  EXPECT_EQ(readText(c / "pose1.obj"), pose1_before);
  EXPECT_EQ(readText(c / "pose2.obj"), pose2_before);
  EXPECT_EQ(readText(c / "truth.tgf"), truth_before);
  EXPECT_EQ(readText(c / "asset.odsk"), asset_before);
  EXPECT_EQ(readText(c / "frame1.obj"), frame1_before);
  EXPECT_EQ(readText(c / "patch.obj"), patch_before);
  EXPECT_TRUE(fs::is_symlink(c / "alias.obj"));
  EXPECT_FALSE(fs::exists(c / "patch.glb"));
}

// Two outputs of one command that land in one file are refused (the weights once replaced the
// skeleton through a link), and an output that fails late replaces none written before it.
TEST_F(BadInputCli, RigOutputsAreCheckedBeforeAnyIsWritten) {
  const fs::path c = dir() / "rig_outputs";
  fs::create_directories(c / "folder.dmat");
  fs::remove(c / "link.dmat");
  fs::create_symlink("skeleton.tgf", c / "link.dmat");
  writeText(c / "skeleton.tgf", "old\n");
  const std::string skeleton = (c / "skeleton.tgf").string();
  const std::vector<std::pair<std::vector<std::string>, std::pair<int, std::string>>> cases{
      {{"rig", in("good1.obj"), "-o", skeleton, "--weights", (c / "link.dmat").string()},
       {2, "skeleton.tgf and " + (c / "link.dmat").string() + " name the same file"}},
      {{"rig", in("good1.obj"), "-o", skeleton, "--weights", (c / "folder.dmat").string()}, {2, "folder.dmat is a folder"}},
  };
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const Outcome r = runOdeskin(cases[i].first, dir() / "io" / ("rig_outputs" + std::to_string(i)));
    expectOneErrorLine(r, cases[i].second.first, {cases[i].second.second}, commandLine(cases[i].first));
    EXPECT_EQ(readText(c / "skeleton.tgf"), "old\n") << commandLine(cases[i].first);
  }
  // The message lists the devices there are, on more lines.
  const Outcome no_device = runOdeskin({"--device", "no-such-device", "rig", in("good1.obj"), "-o", skeleton, "--weights",
                                        (c / "w.dmat").string(), "--png", (c / "p.png").string()},
                                       dir() / "io" / "rig_outputs_device");
  EXPECT_EQ(no_device.status, 1) << no_device.err;
  EXPECT_NE(no_device.err.find("rig: --png: drawing needs a Vulkan device"), std::string::npos) << no_device.err;
  EXPECT_EQ(readText(c / "skeleton.tgf"), "old\n");
  EXPECT_FALSE(fs::exists(c / "w.dmat"));
}

// A file output that names a folder is refused before any work: `fit ... -o out/` fitted, failed to
// write and left out/ behind; `bench --json out/` did so after minutes of timing.
TEST_F(BadInputCli, FileOutputsThatNameAFolderAreRefusedBeforeAnyWork) {
  const fs::path c = dir() / "folders";
  fs::create_directories(c / "existing");
  fs::create_directories(c / "seq" / "f_0003.obj");
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases{
      {{"fit", in("good1.obj"), in("good2.obj"), "-o", (c / "new1").string() + "/"}, "new1/ names a folder"},
      {{"fit", in("good1.obj"), in("good2.obj"), "-o", (c / "existing").string()}, "existing is a folder"},
      {{"evaluate", in("good1.obj"), in("good2.obj"), in("good3.obj"), "--keys", "0,2", "--json", (c / "new2").string() + "/"},
       "new2/ names a folder"},
      {{"bench", "--no-fit", "--sizes", "1000", "--terms", "3", "--backends", "cpu_ref", "--json", (c / "new3").string() + "/"},
       "new3/ names a folder"},
      {{"play", in("cyl.odsk"), "--fps", "4", "-o", (c / "seq" / "f_%04d.obj").string()}, "f_0003.obj is a folder"},
  };
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const Outcome r = runOdeskin(cases[i].first, dir() / "io" / ("folders" + std::to_string(i)));
    expectOneErrorLine(r, 2, {cases[i].second}, commandLine(cases[i].first));
  }
  for (const char* name : {"new1", "new2", "new3"}) EXPECT_FALSE(fs::exists(c / name)) << name;
  EXPECT_FALSE(fs::exists(c / "seq" / "f_0000.obj")) << "frames before the folder were written";
}

// A device behind an input's name is refused before any read; /dev/zero was read until memory ran
// out. The links here name /dev/null, so a regression fails on the message rather than hanging.
TEST_F(BadInputCli, DevicesBehindInputNamesAreRefused) {
  const fs::path c = dir() / "devices";
  fs::create_directories(c);
  for (const char* name : {"dev.obj", "dev.odsk", "dev.json", "dev.tgf", "dev.dmat"}) {
    fs::remove(c / name);
    fs::create_symlink("/dev/null", c / name);
  }
  auto at = [&](const char* name) { return (c / name).string(); };
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases{
      {{"render", at("dev.obj"), "-o", at("x.png")}, "dev.obj: is a device, not a file"},
      {{"fit", at("dev.obj"), in("good2.obj"), "-o", at("x.odsk")}, "dev.obj: is a device, not a file"},
      {{"info", at("dev.odsk")}, "dev.odsk: is a device, not a file"},
      {{"play", at("dev.odsk"), "--t", "0", "-o", at("x.obj")}, "dev.odsk: is a device, not a file"},
      {{"surface", at("dev.json"), "-o", at("x.glb")}, "dev.json: is a device, not a file"},
      {{"reconstruct", at("dev.obj"), "-o", at("x.obj")}, "dev.obj: is a device, not a file"},
      {{"rig", at("dev.obj"), "-o", at("x.tgf")}, "dev.obj: is a device, not a file"},
      {{"fit", in("good1.obj"), in("good2.obj"), "--bind", in("good1.obj"), "--rig", at("dev.tgf"), "--weights",
        at("dev.dmat"), "-o", at("x.odsk")}, "is a device, not a file"},
  };
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const Outcome r = runOdeskin(cases[i].first, dir() / "io" / ("devices" + std::to_string(i)));
    expectOneErrorLine(r, 1, {cases[i].second}, commandLine(cases[i].first));
  }
}

TEST_F(BadInputCli, UnwritableOutputsFailWithoutPartialFiles) {
  // A regular file where a folder should be: even root cannot create under it.
  const fs::path blocker = dir() / "unwritable" / "blocker";
  writeText(blocker, "a file, not a folder\n");
  const std::string under = (blocker / "sub" / "x").string();
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases{
      {{"fit", in("good1.obj"), in("good2.obj"), "-o", under + ".odsk"}, "blocker"},
      {{"play", in("cyl.odsk"), "--t", "0.5", "-o", under + ".obj"}, "blocker"},
      {{"export", in("cyl.odsk"), "-o", under + ".glb"}, "blocker"},
      {{"surface", in("patch.json"), "-o", under + ".glb"}, "blocker"},
      {{"blend", "--example", "3.17", "-o", under + ".obj"}, "blocker"},
      {{"rig", in("good1.obj"), "-o", under + ".tgf"}, "blocker"},
      {{"reconstruct", in("good1.obj"), "-o", under + ".obj"}, "blocker"},
      {{"evaluate", in("good1.obj"), in("good2.obj"), in("good3.obj"), "--keys", "0,2", "--json", under + ".json"},
       "blocker"},
      {{"play", in("cyl.odsk"), "--fps", "4", "-o", under + ".pc2"}, "blocker"},
      {{"play", in("cyl.odsk"), "--fps", "4", "-o", under + ".mdd"}, "blocker"},
      {{"compare", in("good1.obj"), in("good2.obj"), "-o", under + ".ply"}, "blocker"},
  };
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const Outcome r = runOdeskin(cases[i].first, dir() / "io" / ("unwritable" + std::to_string(i)));
    expectOneErrorLine(r, 1, {cases[i].second}, commandLine(cases[i].first));
  }
  EXPECT_EQ(snapshot(dir() / "unwritable").size(), 1u) << "only the blocker file may be there";
  EXPECT_EQ(readText(blocker), "a file, not a folder\n");
}

// The file size limit makes the output's write fail part way, as a full disk would: the command
// says so and neither a partial output nor its temporary file is left, and the old file survives.
TEST_F(BadInputCli, AWriteThatFailsPartWayLeavesTheOldFile) {
  const fs::path out_dir = dir() / "full_disk";
  const std::vector<std::pair<std::string, std::vector<std::string>>> cases{
      {"x.odsk", {"fit", in("good1.obj"), in("good2.obj"), "-q", "-o", (out_dir / "x.odsk").string()}},
      {"x.glb", {"export", in("cyl.odsk"), "-q", "-o", (out_dir / "x.glb").string()}},
      {"x.obj", {"play", in("cyl.odsk"), "--t", "0.5", "-q", "-o", (out_dir / "x.obj").string()}},
      {"s.glb", {"surface", in("patch.json"), "-q", "-o", (out_dir / "s.glb").string()}},
      {"x.pc2", {"play", in("cyl.odsk"), "--fps", "4", "-q", "-o", (out_dir / "x.pc2").string()}},
      {"x.mdd", {"play", in("cyl.odsk"), "--fps", "4", "-q", "-o", (out_dir / "x.mdd").string()}},
      {"x.ply", {"compare", in("good1.obj"), in("good2.obj"), "-q", "-o", (out_dir / "x.ply").string()}},
  };
  for (const auto& [name, args] : cases) {
    writeText(out_dir / name, "precious\n");
    const std::map<std::string, std::string> before = snapshot(out_dir);
    RunOptions limited;
    limited.file_size_limit = 4096;  // every output here is larger; stderr's one line is not
    const Outcome r = runOdeskin(args, dir() / "io" / ("full_" + name), limited);
    expectOneErrorLine(r, 1, {(out_dir / name).string(), "write failed"}, commandLine(args));
    EXPECT_EQ(snapshot(out_dir), before) << name;
  }
}

// A command with several outputs whose later output cannot be written (a link to /dev/full, as a
// full disk) removes the outputs it already wrote: a failed command leaves none of them.
TEST_F(BadInputCli, ALaterOutputThatFailsRemovesTheEarlierOnes) {
  ASSERT_TRUE(fs::exists("/dev/full")) << "the test needs Linux's /dev/full";
  struct Case {
    std::string name;
    std::vector<std::string> args;  // {dir} is the case's folder
    std::string full;               // the output linked to /dev/full
  };
  const std::vector<Case> cases{
      {"play_frames", {"play", in("cyl.odsk"), "--fps", "4", "-o", "{dir}/f_%02d.obj"}, "f_02.obj"},
      {"rig_weights", {"rig", in("good1.obj"), "--template", "none", "-o", "{dir}/s.tgf", "--weights", "{dir}/w.dmat"},
       "w.dmat"},
      {"rig_gltf", {"rig", in("good1.obj"), "--template", "none", "-o", "{dir}/s.tgf", "--gltf", "{dir}/s.glb"}, "s.glb"},
      {"compare_json", {"compare", in("good1.obj"), in("good2.obj"), "-o", "{dir}/e.ply", "--json", "{dir}/e.json"},
       "e.json"},
      {"evaluate_json", {"evaluate", in("good1.obj"), in("good2.obj"), in("good3.obj"), "--keys", "0,2", "--methods", "lbs",
                         "--json", "{dir}/r.json"},
       "r.json"},
  };
  for (const Case& c : cases) {
    const fs::path out_dir = dir() / "later_output" / c.name;
    fs::create_directories(out_dir);
    fs::create_symlink("/dev/full", out_dir / c.full);
    std::vector<std::string> args = c.args;
    for (std::string& a : args) {
      if (const std::size_t at = a.find("{dir}"); at != std::string::npos) a.replace(at, 5, out_dir.string());
    }
    const Outcome r = runOdeskin(args, dir() / "io" / ("later_" + c.name));
    expectOneErrorLine(r, 1, {c.full, "write failed"}, commandLine(args));
    std::vector<std::string> left;
    for (const fs::directory_entry& e : fs::directory_iterator(out_dir)) left.push_back(e.path().filename().string());
    EXPECT_EQ(left, std::vector<std::string>{c.full}) << c.name << ": only the link to /dev/full may be left";
  }
}

// An input the limits accept but this machine (here: 1 GiB of address space) cannot hold ends
// with std::bad_alloc caught in main: exit 1, one line, no output; never an abort.
TEST_F(BadInputCli, RunningOutOfMemoryIsAnErrorNotACrash) {
  if (testing::kSanitized) GTEST_SKIP() << "RLIMIT_AS does not work under a sanitizer";
  const fs::path out_dir = dir() / "out_of_memory";
  RunOptions limited;
  limited.address_space_limit = 1L << 30;
  const std::vector<std::vector<std::string>> cases{
      {"blend", "--example", "3.17", "--res", "5000,9000", "-o", (out_dir / "big.obj").string()},
      {"surface", in("patch.json"), "--res", "8000,8000", "-o", (out_dir / "big.glb").string()}};
  for (const std::vector<std::string>& args : cases) {
    const Outcome r = runOdeskin(args, dir() / "io" / "out_of_memory", limited);
    expectOneErrorLine(r, 1, {args[0] + ": out of memory"}, commandLine(args));
  }
  EXPECT_TRUE(snapshot(out_dir).empty());
}

TEST_F(BadInputCli, GoodInputsSucceed) {
  const fs::path out = dir() / "good";
  const std::vector<std::pair<std::vector<std::string>, fs::path>> cases{
      {{"fit", in("good1.obj"), in("good2.obj"), "-q", "-o", (out / "auto.odsk").string()}, out / "auto.odsk"},
      {{"play", in("cyl.odsk"), "--t", "0.5", "-q", "-o", (out / "mid.obj").string()}, out / "mid.obj"},
      {{"export", in("cyl.odsk"), "-q", "-o", (out / "cyl.glb").string()}, out / "cyl.glb"},
      {{"info", in("cyl.odsk")}, {}},
      // A vertex in no face, in every pose: skinned by the automatic rig's bones like any other.
      {{"fit", in("unbound1.obj"), in("unbound.obj"), "-q", "-o", (out / "unbound.odsk").string()}, out / "unbound.odsk"},
      {{"surface", in("patch.json"), "-q", "-o", (out / "patch.glb").string()}, out / "patch.glb"},
      {{"blend", "--example", "3.17", "-q", "-o", (out / "blend.obj").string()}, out / "blend.obj"},
      {{"play", in("cyl.odsk"), "--fps", "4", "-q", "-o", (out / "cyl.pc2").string()}, out / "cyl.pc2"},
      {{"compare", in("good1.obj"), in("good2.obj"), "-q", "-o", (out / "good.ply").string(), "--json",
        (out / "good.json").string()}, out / "good.ply"},
      // More threads than the machine runs: capped, without TBB's own warning on stderr.
      {{"demo", "--backend", "cpu", "--threads", "100000", "--frames", "2", "-q", "-o", (out / "demo").string()}, {}},
      // Weights that sum to one within the reader's tolerance, and a material with negative
      // damping: accepted; the latter with one warning (MATH.md 5.4).
      {{"fit", in("good1.obj"), in("good2.obj"), "--material", "1,-1,3,0", "-o", (out / "neg.odsk").string()},
       out / "neg.odsk"},
  };
  for (const auto& [args, file] : cases) {
    const Outcome r = runOdeskin(args, dir() / "io" / "good");
    ASSERT_TRUE(r.exited) << commandLine(args);
    EXPECT_EQ(r.status, 0) << commandLine(args) << "\n" << r.err;
    if (!file.empty()) {
      EXPECT_TRUE(fs::is_regular_file(file)) << file;
    }
    if (args[0] == "fit" && args[3] == "--material") {
      EXPECT_EQ(r.err.rfind("warning: fit: --material '1,-1,3,0': eta/rho < 0", 0), 0u) << r.err;
      EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    } else if (std::find(args.begin(), args.end(), "-q") != args.end()) {
      EXPECT_EQ(r.err, "") << commandLine(args);
      EXPECT_EQ(r.out, "") << commandLine(args);  // --quiet: no summary either
    }
  }
  // No temporary files beside the outputs.
  for (const fs::directory_entry& e : fs::directory_iterator(out)) {
    EXPECT_EQ(e.path().string().find(".tmp"), std::string::npos) << e.path();
  }
}

// Vertices the geometric transform binds rigidly (their LBS map near singular at a key) change the
// fit; the summary counts them, as docs/pipeline.md says.
TEST_F(BadInputCli, FitSaysHowManyVerticesFollowTheirBoneRigidly) {
  const std::string cats = std::string(ODESKIN_DATA_DIR) + "/cat-poses/";
  const fs::path out = dir() / "rigid_count";
  const Outcome r = runOdeskin({"fit", cats + "cat-00.obj", cats + "cat-01.obj", "-o", (out / "c.odsk").string()}, out);
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("\nrigid: 22 vertices whose skinning is near singular at a key (nearly opposed bones) follow "
                       "their dominant bone\n"),
            std::string::npos)
      << r.out;
}

// fit --rig curves hands --up to the curve rig's templates: the cat turned z-up is a quadruped only
// when the fit is told that z is up (CurveRig.FitPipelineTakesTheMeshsUpAxis has the pipeline's side).
TEST_F(BadInputCli, FitGivesTheCurveRigItsUpAxis) {
  const fs::path out = dir() / "up_axis";
  std::vector<std::string> poses;
  for (const char* name : {"cat-00.obj", "cat-01.obj"}) {
    std::ifstream in(fs::path(ODESKIN_DATA_DIR) / "cat-poses" / name);
    std::ostringstream turned;
    turned.precision(17);
    for (std::string line; std::getline(in, line);) {
      if (line.rfind("v ", 0) == 0) {  // (x, y, z) -> (x, -z, y): y-up to z-up
        std::istringstream v(line.substr(2));
        double x = 0.0, y = 0.0, z = 0.0;
        v >> x >> y >> z;
        turned << "v " << x << ' ' << -z << ' ' << y << '\n';
      } else {
        turned << line << '\n';
      }
    }
    poses.push_back((out / name).string());
    writeText(poses.back(), turned.str());
  }
  const Outcome as_y = runOdeskin({"fit", poses[0], poses[1], "--rig", "curves", "-o", (out / "y.odsk").string()}, out);
  EXPECT_EQ(as_y.status, 0) << as_y.err;
  EXPECT_EQ(as_y.out.find("template quadruped"), std::string::npos) << as_y.out;
  const Outcome as_z =
      runOdeskin({"fit", poses[0], poses[1], "--rig", "curves", "--up", "z", "-o", (out / "z.odsk").string()}, out);
  EXPECT_EQ(as_z.status, 0) << as_z.err;
  EXPECT_NE(as_z.out.find("template quadruped"), std::string::npos) << as_z.out;
}

TEST_F(BadInputCli, GltfTimesOutsideTheAnimationAreFittedWithAWarning) {
  const fs::path out = dir() / "gltf_times";
  const std::string glb = (out / "cyl.glb").string();
  ASSERT_EQ(runOdeskin({"export", in("cyl.odsk"), "-q", "-o", glb}, out).status, 0);
  // The exported animation keys the asset's two poses at 0 and 1 s; glTF holds its end after it.
  const Outcome r = runOdeskin({"fit", glb, "--times", "0.5,100", "-o", (out / "x.odsk").string()}, out);
  EXPECT_EQ(r.status, 0) << r.err;
  // cyl.odsk was fitted with --bind: its export holds the bind mesh in its buffers and the first key
  // pose in its joints' rest, and the reader says so before the time it held.
  EXPECT_EQ(r.err, "warning: fit: " + glb +
                       ": the nodes' rest pose moves the mesh by up to 0.48474221 of its box (joint 3 'bone3': its "
                       "inverse bind matrix does not undo its rest transform), so key pose 0, the mesh as its buffers "
                       "hold it, is not what viewers show at rest\n"
                       "warning: fit: " + glb +
                       ": 100 s is outside odeskin's keyframes (0 to 1 s); glTF holds the end keyframe there, so "
                       "this pose is the one at 1 s\n");
  const Outcome quiet = runOdeskin({"fit", glb, "--times", "0.5,100", "-q", "-o", (out / "q.odsk").string()}, out);
  EXPECT_EQ(quiet.status, 0) << quiet.err;
  EXPECT_EQ(quiet.err, "");
  // The file's skin is the rig, so --bones would be ignored; with --rig auto it applies.
  const Outcome bones = runOdeskin({"fit", glb, "--times", "0,1", "--bones", "3", "-o", (out / "b.odsk").string()}, out);
  expectOneErrorLine(bones, 2, {"fit: --bones applies to the automatic rig, and " + glb + " brings its own skin"}, "--bones");
  EXPECT_FALSE(fs::exists(out / "b.odsk"));
}

// Output that never reached stdout (here a pipe nobody reads; a full disk alike) fails the command.
TEST_F(BadInputCli, AStandardOutputThatCannotBeWrittenIsAnError) {
  RunOptions options;
  options.stdout_unread = true;
  const Outcome info = runOdeskin({"info", in("cyl.odsk")}, dir() / "io" / "unread", options);
  expectOneErrorLine(info, 1, {"info: standard output: write failed: ", "Broken pipe"}, "info, stdout unread");
  // Nothing to print: nothing fails.
  const fs::path out = dir() / "unread" / "mid.obj";
  const Outcome quiet = runOdeskin({"play", in("cyl.odsk"), "--t", "0.5", "-q", "-o", out.string()},
                                   dir() / "io" / "unread", options);
  EXPECT_TRUE(quiet.exited && quiet.status == 0) << quiet.err;
  EXPECT_TRUE(fs::is_regular_file(out));
}

// A signal while an output is being written: the command line's handler removes the temporary
// (engine/core/pending_files.hpp) and the process still ends by the signal.
TEST_F(BadInputCli, AnInterruptedWriteLeavesNoTemporaryFile) {
  const fs::path files = dir() / "interrupted" / "files";
  const auto temporaries = [&files] {
    std::vector<fs::path> found;
    for (const fs::directory_entry& e : fs::directory_iterator(files)) {
      if (e.path().filename().string().find(".tmp") != std::string::npos) found.push_back(e.path());
    }
    return found;
  };
  struct Named {
    int number;
    const char* name;
  };
  for (const Named signal : {Named{SIGTERM, "SIGTERM"}, Named{SIGINT, "SIGINT"}, Named{SIGHUP, "SIGHUP"}}) {
    const int signal_number = signal.number;
    const char* const name = signal.name;
    bool ended_by_signal = false;
    // The signal is sent once the temporary appears; the 72 MB grid takes about 0.1 s to write, but
    // a poller held off the CPU until after the rename misses it, so a few tries are allowed.
    for (int attempt = 0; attempt < 5 && !ended_by_signal; ++attempt) {
      fs::remove_all(files);
      fs::create_directories(files);
      RunOptions options;
      options.while_running = [&](pid_t pid) {
        const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
        while (std::chrono::steady_clock::now() < deadline && !fs::exists(files / "grid.obj")) {
          if (!temporaries().empty()) {
            ::kill(pid, signal_number);
            return;
          }
          std::this_thread::sleep_for(std::chrono::microseconds(200));
        }
      };
      const std::vector<std::string> args{"blend", "--example", "3.17", "--res", "1000,1000", "-q", "-o",
                                          (files / "grid.obj").string()};
      const Outcome r = runOdeskin(args, dir() / "interrupted" / "io", options);
      ended_by_signal = !r.exited && r.status == signal_number;
      EXPECT_TRUE(ended_by_signal || (r.exited && r.status == 0)) << name << ": " << r.status;
      EXPECT_EQ(temporaries(), std::vector<fs::path>{}) << name;
    }
    EXPECT_TRUE(ended_by_signal) << name << " never arrived during the write";
  }
}

// With no driver at all the loader fails vkCreateInstance, before the device check's hint: the line
// used to be "vkCreateInstance(&info, nullptr, &instance.instance_) failed: VK_ERROR_INCOMPATIBLE_DRIVER".
TEST_F(BadInputCli, NoVulkanDriverSaysWhatToInstall) {
  const fs::path empty = dir() / "no_drivers";
  fs::create_directories(empty);
  RunOptions env;
  env.env["VK_DRIVER_FILES"] = empty.string();
  env.env["VK_ICD_FILENAMES"] = empty.string();
  const std::vector<std::string> args{"play", in("cyl.odsk"), "--t", "0.5", "--backend", "vulkan", "-o",
                                      (dir() / "no_driver.obj").string()};
  const Outcome r = runOdeskin(args, dir() / "io" / "no_driver", env);
  expectOneErrorLine(r, 1, {"play: no Vulkan driver (vkCreateInstance: VK_ERROR_INCOMPATIBLE_DRIVER): install "
                            "mesa-vulkan-drivers"}, commandLine(args));
  EXPECT_FALSE(fs::exists(dir() / "no_driver.obj"));
}

// ---- Vulkan faults -----------------------------------------------------------------------------------

struct Fault {
  std::string name;     // ODESKIN_VK_FAULT
  std::string message;  // what the line must say
};

const std::vector<Fault> kFaults{{"no-device", "no Vulkan device"},
                                 {"device-create", "vkCreateDevice failed: VK_ERROR_INITIALIZATION_FAILED"},
                                 {"out-of-memory", "vkAllocateMemory failed: VK_ERROR_OUT_OF_DEVICE_MEMORY"},
                                 {"device-lost", "vkQueueSubmit failed: VK_ERROR_DEVICE_LOST"}};

class VulkanFaults : public BadInputCli {
 protected:
  void SetUp() override {
    // The faults replace a working device's calls; without one every fault reads "no Vulkan device".
    const Outcome probe = runOdeskin({"play", in("cyl.odsk"), "--t", "0.5", "--backend", "vulkan", "-q", "-o",
                                      (dir() / "probe" / "probe.obj").string()},
                                     dir() / "io" / "probe");
    if (probe.exited && probe.status == 0) return;
    if (testing::gpuRequired()) FAIL() << "ODESKIN_REQUIRE_GPU=1 but no Vulkan device: " << probe.err;
    GTEST_SKIP() << "no Vulkan device: " << probe.err;
  }

  // Every fault with --backend auto falls back (exit 0, the output written, one note) and with
  // --backend vulkan fails (exit 1, one error line, the old output untouched).
  // `output` is the -o argument, `written` the (first) file it makes.
  void expectFallbackOrFailure(const std::string& verb, const std::vector<std::string>& args, const std::string& output,
                               const std::string& written, const std::string& note) {
    for (const Fault& fault : kFaults) {
      RunOptions env;
      env.env["ODESKIN_VK_FAULT"] = fault.name;
      const fs::path out_dir = dir() / "faults" / (verb + "_" + fault.name);
      for (const std::string backend : {"auto", "vulkan"}) {
        fs::remove_all(out_dir);
        writeText(out_dir / written, "precious\n");
        std::vector<std::string> full = args;
        full.insert(full.end(), {"--backend", backend, "-o", (out_dir / output).string()});
        const Outcome r = runOdeskin(full, dir() / "io" / ("fault_" + verb), env);
        const std::string what = "ODESKIN_VK_FAULT=" + fault.name + " " + commandLine(full);
        ASSERT_TRUE(r.exited) << what << ": signal " << r.status;
        if (backend == std::string("auto")) {
          EXPECT_EQ(r.status, 0) << what << "\n" << r.err;
          EXPECT_EQ(r.err.rfind("note: Vulkan failed (", 0), 0u) << what << "\n" << r.err;
          EXPECT_NE(r.err.find(fault.message), std::string::npos) << what << "\n" << r.err;
          EXPECT_NE(r.err.find(note), std::string::npos) << what << "\n" << r.err;
          EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << what << "\n" << r.err;
          EXPECT_NE(readText(out_dir / written), "precious\n") << what << ": no output written";
        } else {
          expectOneErrorLine(r, 1, {verb + ": ", fault.message}, what);
          EXPECT_EQ(readText(out_dir / written), "precious\n") << what;
          EXPECT_EQ(snapshot(out_dir).size(), 1u) << what;
        }
      }
    }
  }
};

TEST_F(VulkanFaults, PlayFallsBackOrFails) {
  expectFallbackOrFailure("play", {"play", in("cyl.odsk"), "--fps", "4"}, "cyl_%02d.obj", "cyl_00.obj",
                          "); playing on the CPU");
}

TEST_F(VulkanFaults, SurfaceFallsBackOrFails) {
  expectFallbackOrFailure("surface", {"surface", in("patch.json")}, "patch.glb", "patch.glb",
                          "); tessellating on the CPU");
}

TEST_F(VulkanFaults, RenderAndDemoSayWhatFailed) {
  for (const Fault& fault : kFaults) {
    RunOptions env;
    env.env["ODESKIN_VK_FAULT"] = fault.name;
    const fs::path out_dir = dir() / "faults" / ("render_" + fault.name);
    // render has no CPU path: exit 1 and one line.
    const std::vector<std::string> render{"render", in("good1.obj"), "-o", (out_dir / "x.png").string()};
    expectOneErrorLine(runOdeskin(render, dir() / "io" / "fault_render", env), 1, {"render: ", fault.message},
                       fault.name + ": " + commandLine(render));
    EXPECT_FALSE(fs::exists(out_dir / "x.png"));
    // demo --backend auto (its default) finishes on the CPU; --backend vulkan fails.
    const std::vector<std::string> demo{"demo", "--frames", "2", "-o", (out_dir / "demo").string()};
    const Outcome fallback = runOdeskin(demo, dir() / "io" / "fault_demo", env);
    EXPECT_TRUE(fallback.exited && fallback.status == 0) << fault.name << "\n" << fallback.err;
    // demo's notes go to stdout with its report.
    EXPECT_NE(fallback.out.find("note: Vulkan failed (" + fault.message), std::string::npos) << fallback.out;
    EXPECT_NE(fallback.out.find("); using the CPU backend"), std::string::npos) << fallback.out;
    std::vector<std::string> demo_vulkan = demo;
    demo_vulkan.insert(demo_vulkan.end(), {"--backend", "vulkan"});
    expectOneErrorLine(runOdeskin(demo_vulkan, dir() / "io" / "fault_demo", env), 1, {"demo: ", fault.message},
                       fault.name + ": " + commandLine(demo_vulkan));
  }
}

TEST_F(VulkanFaults, AnUnknownFaultIsIgnoredWithAWarning) {
  RunOptions env;
  env.env["ODESKIN_VK_FAULT"] = "gremlins";
  const std::vector<std::string> args{"play", in("cyl.odsk"), "--t", "0.5", "--backend", "vulkan", "-q", "-o",
                                      (dir() / "faults" / "unknown.obj").string()};
  const Outcome r = runOdeskin(args, dir() / "io" / "fault_unknown", env);
  ASSERT_TRUE(r.exited);
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err.rfind("odeskin: warning: ODESKIN_VK_FAULT=gremlins ignored", 0), 0u) << r.err;
}

}  // namespace
}  // namespace odeskin
