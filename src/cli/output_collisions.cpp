#include "cli/output_collisions.h"

#include <optional>
#include <system_error>
#include <vector>

#include <sys/stat.h>

#include "app/scene_input.h"
#include "bench/src/bench_commands.h"
#include "io/output_path.h"

namespace rp::cli {
namespace {

namespace fs = std::filesystem;

// What a path is as a file: device and inode when it exists, else its resolved absolute name.
struct Identity {
  bool exists = false;
  dev_t dev = 0;
  ino_t ino = 0;
  fs::path name;
  bool operator==(const Identity& o) const {
    return exists == o.exists && (exists ? dev == o.dev && ino == o.ino : name == o.name);
  }
};

std::optional<Identity> identify(const fs::path& path) {
  Identity id;
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0) {
    id.exists = true;
    id.dev = st.st_dev;
    id.ino = st.st_ino;
    return id;
  }
  std::error_code ec;
  id.name = fs::weakly_canonical(fs::absolute(path, ec), ec);
  if (ec) return std::nullopt;
  return id;
}

// An output as it will be written: replaced files only (in-place targets are appended to).
std::optional<Identity> identify_output(const fs::path& path) {
  try {
    const io::OutputTarget target = io::resolve_output(path);
    if (target.kind != io::OutputTarget::Kind::kReplace) return std::nullopt;
    return identify(target.path);
  } catch (const std::exception&) {
    return std::nullopt;  // a directory, a socket, a loop: check_output_file says so later
  }
}

struct Named {
  std::string option;  // "--json", or "--json (the default with --devices)"
  std::string path;
};

std::string describe(const Named& a, const Named& b) {
  if (a.path == b.path) return a.option + " and " + b.option + " both name " + a.path;
  return a.option + " " + a.path + " and " + b.option + " " + b.path + " are the same file";
}

// The first collision among `outputs`, then between an output and an input.
std::string first_collision(const std::vector<Named>& outputs, const std::vector<Named>& inputs) {
  for (size_t i = 0; i < outputs.size(); ++i)
    for (size_t j = i + 1; j < outputs.size(); ++j)
      if (same_file(outputs[i].path, outputs[j].path))
        return describe(outputs[i], outputs[j]) + "; each output needs a file of its own";
  for (const Named& out : outputs)
    for (const Named& in : inputs)
      if (same_file(out.path, in.path))
        return describe(out, in) + ": " + out.option + " would overwrite the file " +
               in.option + " reads; write to another file";
  return "";
}

void add(std::vector<Named>& list, const char* option, const std::string& path) {
  if (!path.empty()) list.push_back({option, path});
}

// render and run: the replayed log, the scene file.
std::vector<Named> inputs_of(const app::CommonOptions& common, const app::SimulationArgs& sim) {
  std::vector<Named> inputs;
  add(inputs, "--replay", sim.replay);
  if (!app::is_demo_scene(common.scene)) add(inputs, "--scene", common.scene);
  return inputs;
}

}  // namespace

bool same_file(const fs::path& output, const fs::path& other) {
  const std::optional<Identity> a = identify_output(output);
  if (!a) return false;
  const std::optional<Identity> b = identify(other);
  return b && *a == *b;
}

std::string find_output_collision(const ParsedCommand& command) {
  std::vector<Named> outputs;
  switch (command.kind) {
    case ParsedCommand::Kind::kRender:
      add(outputs, "--video", command.render.video);
      return first_collision(outputs, inputs_of(command.common, command.render.sim));
    case ParsedCommand::Kind::kRun:
      add(outputs, "--record", command.run.record);
      add(outputs, "--capture", command.run.capture);
      return first_collision(outputs, inputs_of(command.common, command.run.sim));
    case ParsedCommand::Kind::kBench: {
      const bench::BenchOptions& given = command.bench;
      const bench::BenchOptions b = bench::with_default_outputs(given);
      add(outputs, given.json.empty() ? "--json (the default with --devices)" : "--json", b.json);
      add(outputs, "--markdown", b.markdown);
      add(outputs, given.chart.empty() ? "--chart (the default with --devices)" : "--chart",
          b.chart);
      std::vector<Named> inputs;
      add(inputs, "--replay", given.sim.replay);
      if (given.scene != "default" && given.scene != "busy") add(inputs, "--scene", given.scene);
      return first_collision(outputs, inputs);
    }
    case ParsedCommand::Kind::kDevices:
    case ParsedCommand::Kind::kExport: return "";
  }
  return "";
}

}  // namespace rp::cli
