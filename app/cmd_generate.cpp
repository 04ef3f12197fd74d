// `intrinsic generate`: the built-in surfaces (the README's default input).
#include <iostream>

#include "command.h"
#include "intrinsic/generate.h"
#include "intrinsic/io.h"

namespace intrinsic::app {

void register_generate(CLI::App& app, Runner& run) {
  struct Args {
    std::string name, output;
    GenerateOptions options;
  };
  auto a = std::make_shared<Args>();
  CLI::App* cmd = app.add_subcommand("generate", "Write a built-in irregular test surface");
  cmd->add_option("surface", a->name, "wave | cap | flat | strip | two-disks | sphere | torus | genus2 (closed: for `intrinsic atlas`)")
      ->check(CLI::IsMember({"wave", "cap", "flat", "strip", "two-disks", "sphere", "torus", "genus2"}))
      ->required();
  cmd->add_option("-o,--output", a->output, "Output mesh (.obj or .ply)")->required();
  cmd->add_option("--rings", a->options.rings, "Radial resolution (about 3*rings^2 vertices)")
      ->check(CLI::Range(1, 5000))
      ->capture_default_str();
  cmd->add_option("--jitter", a->options.jitter, "Irregularity, 0..0.9")->check(CLI::Range(0.0, 0.9))->capture_default_str();
  cmd->add_option("--seed", a->options.seed, "Random seed")->capture_default_str();
  cmd->callback([&run, a] {
    run = [a] {
      check_output_mesh_path(a->output);
      const MeshData m = generate_surface(a->name, a->options);
      write_mesh(a->output, m.V, m.F, MatrixX2d());
      std::cout << a->output << ": " << m.V.rows() << " vertices, " << m.F.rows() << " faces\n";
      return 0;
    };
  });
}

}  // namespace intrinsic::app
