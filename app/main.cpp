// The `intrinsic` command-line tool: subcommands, and the one place where
// errors become messages and exit codes (0 ok, 1 usage, 2 input, 3 numerical,
// 4 output; see docs/formats.md).
#include <dlfcn.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <iostream>

#include "command.h"
#include "intrinsic/error.h"
#include "intrinsic/io.h"

namespace {

// One OpenBLAS thread for this process, unless the user chose a number.
// The library never runs BLAS on more than one thread: its factorizations
// are parallel above BLAS and hold OpenBLAS at one thread while they run
// (src/solve/solver_threads.cpp). But OpenBLAS starts a worker thread per
// core when it loads, and each spins on sched_yield for about 0.1 s before
// it sleeps: on 2 cores that took a core from the start of every command
// (a 1,000-face atlas: 0.31 against 0.23 s of CPU). OpenBLAS reads its
// variable before main, so the pool is stopped here; with the count at one
// the library never restarts it. Looked up by name: with another BLAS (or
// none) there is nothing to stop.
void stop_blas_worker_threads() {
  if (std::getenv("OPENBLAS_NUM_THREADS") || std::getenv("OMP_NUM_THREADS")) return;
  using SetThreads = void (*)(int);
  using Shutdown = int (*)();
  const auto set_threads = reinterpret_cast<SetThreads>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads"));
  const auto shutdown = reinterpret_cast<Shutdown>(dlsym(RTLD_DEFAULT, "blas_thread_shutdown_"));
  if (!set_threads || !shutdown) return;
  set_threads(1);
  shutdown();
}

}  // namespace

namespace intrinsic::app {

double elapsed_ms(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

void check_output_mesh_path(const std::string& path) {
  const std::string ext = mesh_extension(path);
  if (ext != ".obj" && ext != ".ply" && ext != ".glb")
    throw_usage("output '" + path + "': unknown format '" + ext + "' (use .obj, .ply or .glb)");
}

}  // namespace intrinsic::app

int main(int argc, char** argv) {
  using namespace intrinsic;
  stop_blas_worker_threads();
  remove_temporary_files_on_signals();
  CLI::App app{"intrinsic: intrinsic parameterizations of surface meshes (Desbrun, Meyer, Alliez 2002)"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "intrinsic 0.1.0");
  app::Runner run;
  app::register_param(app, run);
  app::register_metrics(app, run);
  app::register_generate(app, run);
  app::register_edit(app, run);
  app::register_render(app, run);
  app::register_compare(app, run);
  app::register_atlas(app, run);
  app::register_formats(app, run);
#ifdef INTRINSIC_HAVE_SERVE
  app::register_serve(app, run);
#endif
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return static_cast<int>(ErrorKind::Usage);
  }
  try {
    return run ? run() : static_cast<int>(ErrorKind::Usage);
  } catch (const Error& e) {
    std::cerr << "intrinsic: error: " << e.what() << "\n";
    return e.exit_code();
  } catch (const std::bad_alloc&) {
    std::cerr << "intrinsic: error: out of memory\n";
    return static_cast<int>(ErrorKind::Input);
  } catch (const std::exception& e) {
    std::cerr << "intrinsic: internal error: " << e.what() << "\n";
    return 5;
  }
}
