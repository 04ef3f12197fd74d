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
    TexturedAssetOptions textured;
    PartsOptions parts;
  };
  auto a = std::make_shared<Args>();
  CLI::App* cmd = app.add_subcommand("generate", "Write a built-in irregular test surface");
  cmd->add_option("surface", a->name, "wave | cap | flat | strip | two-disks | sphere | torus | genus2 (closed: for `intrinsic atlas`) | "
                  "textured (a closed surface in many tiny textured charts, for `atlas --transfer-textures`) | "
                  "parts (many closed and open machine-like parts, for `atlas` at scale) | "
                  "plate | box | l-panel | panel-strip | cylinder | rectangle (CAD-like parts and flat panels, for `atlas` layouts)")
      ->check(CLI::IsMember({"wave", "cap", "flat", "strip", "two-disks", "sphere", "torus", "genus2", "textured", "parts",
                             "plate", "box", "l-panel", "panel-strip", "cylinder", "rectangle"}))
      ->required();
  cmd->add_option("-o,--output", a->output, "Output mesh (.obj or .ply; textured: .glb, .gltf or .obj with .mtl and .png)")
      ->required();
  cmd->add_option("--cells", a->textured.cells, "textured: grid cells along each of the six faces (12*cells^2 triangles)")
      ->check(CLI::Range(1, 2000))
      ->capture_default_str();
  cmd->add_option("--chart-cells", a->textured.chart_cells, "textured: chart side in cells")
      ->check(CLI::Range(1, 2000))
      ->capture_default_str();
  cmd->add_option("--texture-size", a->textured.texture_size, "textured: texture side in texels")
      ->check(CLI::Range(16, 16384))
      ->capture_default_str();
  cmd->add_option("--parts", a->parts.parts, "parts: how many parts")->check(CLI::Range(1, 100000))->capture_default_str();
  cmd->add_option("--faces", a->parts.faces, "parts: about how many faces in all (at least 48 per part)")
      ->check(CLI::Range(48L, 100000000L))
      ->capture_default_str();
  cmd->add_option("--rings", a->options.rings, "Radial resolution (about 3*rings^2 vertices)")
      ->check(CLI::Range(1, 5000))
      ->capture_default_str();
  cmd->add_option("--jitter", a->options.jitter, "Irregularity, 0..0.9")->check(CLI::Range(0.0, 0.9))->capture_default_str();
  cmd->add_option("--seed", a->options.seed, "Random seed")->capture_default_str();
  cmd->callback([&run, a] {
    run = [a] {
      if (a->name == "textured") {
        const TexturedAsset t = generate_textured_asset(a->textured);
        write_textured_asset(a->output, t);
        std::cout << a->output << ": " << t.mesh.V.rows() << " vertices, " << t.mesh.F.rows() << " faces, "
                  << t.texture.width << "x" << t.texture.height << " texture\n";
        return 0;
      }
      check_output_mesh_path(a->output);
      a->parts.seed = a->options.seed;
      const MeshData m = a->name == "parts" ? generate_parts(a->parts).mesh : generate_surface(a->name, a->options);
      write_mesh(a->output, m.V, m.F, MatrixX2d());
      std::cout << a->output << ": " << m.V.rows() << " vertices, " << m.F.rows() << " faces\n";
      return 0;
    };
  });
}

}  // namespace intrinsic::app
