// `intrinsic formats`: what the tool reads and writes, and by which reader
// (docs/cli.md "intrinsic formats"). The table is the library's
// (supported_formats, io.h); this file only prints it.
#include <iomanip>
#include <iostream>

#include <nlohmann/json.hpp>

#include "command.h"
#include "intrinsic/io.h"

namespace intrinsic::app {

namespace {

const char* reader_name(FormatReader r) {
  switch (r) {
    case FormatReader::Own: return "intrinsic";
    case FormatReader::Assimp: return "assimp";
    case FormatReader::None: break;
  }
  return nullptr;
}

nlohmann::json formats_json(const std::vector<FormatInfo>& formats) {
  nlohmann::json rows = nlohmann::json::array();
  for (const FormatInfo& f : formats) {
    const char* reader = reader_name(f.reader);
    rows.push_back({{"extension", f.extension},
                    {"name", f.name},
                    {"reader", reader ? nlohmann::json(reader) : nlohmann::json()},
                    {"gzip", f.gzip},
                    {"writes_mesh", f.writes_mesh},
                    {"writes_atlas", f.writes_atlas}});
  }
  return {{"formats", rows}};
}

void print_text(const std::vector<FormatInfo>& formats) {
  std::cout << "Read by intrinsic's own readers (also gzip-compressed, e.g. .obj.gz):\n";
  for (const FormatInfo& f : formats) {
    if (f.reader != FormatReader::Own) continue;
    std::string writes;
    if (f.writes_mesh) writes += "meshes (param, generate)";
    if (f.writes_atlas) writes += std::string(writes.empty() ? "" : ", ") + "atlases (atlas)";
    std::cout << "  " << std::left << std::setw(10) << f.extension << std::setw(34) << f.name
              << (writes.empty() ? "read only" : "read; written: " + writes) << "\n";
  }
  std::size_t n = 0;
  for (const FormatInfo& f : formats) n += f.reader == FormatReader::Assimp;
  std::cout << "\nRead through assimp (" << n << " extensions; read only, also gzip-compressed):\n";
  for (const FormatInfo& f : formats)
    if (f.reader == FormatReader::Assimp) std::cout << "  " << std::left << std::setw(10) << f.extension << f.name << "\n";
  std::cout << "\nAn atlas of an assimp input is written as .obj (materials as usemtl) or .glb/.gltf.\n";
}

}  // namespace

void register_formats(CLI::App& app, Runner& run) {
  auto json = std::make_shared<bool>(false);
  CLI::App* cmd = app.add_subcommand("formats", "List the file formats read and written, and by which reader");
  cmd->add_flag("--json", *json, "Print the table as JSON");
  cmd->callback([&run, json] {
    run = [json] {
      const std::vector<FormatInfo> formats = supported_formats();
      if (*json) std::cout << formats_json(formats).dump(2) << "\n";
      else print_text(formats);
      return 0;
    };
  });
}

}  // namespace intrinsic::app
