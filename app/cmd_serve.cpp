// `intrinsic serve MESH`: the interactive editor (paper section 4.2) as a
// local web server. GET / serves the page (web/, embedded at build time),
// GET /api/mesh the mesh, POST /api/solve a map, POST /api/optimal_lambda
// and POST /api/optimize_boundary the optimizations of paper section 5
// (docs/cli.md "intrinsic serve"). No file is read after the mesh. Every request
// is answered: errors become HTTP 400/409/413/422/500 with {"error": message}.
// Before any route, the guard (serve/request_guard.h) refuses, in plain
// text, foreign Host headers (400), requests from other pages (Origin,
// Sec-Fetch-Site) or without this launch's token (403), and bodies without
// a Content-Length (411).
#include <iostream>
#include <new>
#include <stdexcept>
#include <nlohmann/json.hpp>

#include "command.h"
#include "intrinsic/error.h"
#include "intrinsic/io.h"
#include "intrinsic/boundary_optimization.h"
#include "intrinsic/optimal_lambda.h"
#include "serve/api_json.h"
#include "serve/optimize_request.h"
#include "serve/request_guard.h"
#include "serve/session_store.h"
#include "web_assets.h"

// Last: httplib.h includes <resolv.h>, whose macro _res breaks Eigen's headers.
#include <httplib.h>

namespace intrinsic::app {
namespace {

struct ServeArgs {
  std::string input, host = "127.0.0.1";
  int port = 8080;
  int max_sessions = 16;
  double max_body_mib = 16;
  std::int64_t max_vertices = ReadOptions().max_vertices;
};

// What the server keeps for its whole life.
struct ServeState {
  MeshData data;
  Mesh mesh;
  std::string mesh_json;
  FaceFrames frames;  // the 3D side of every answer's distortion figures
  std::unique_ptr<SessionStore> sessions;
  HostPolicy hosts;   // known once the port is bound
  std::string token;  // this launch's (request_guard.h)
};

// Not plain "application/json": httplib compresses that exact type (gzip or
// brotli, when the client accepts it), which costs 10x the update itself for
// a large map and gains nothing on a local connection.
const char* const kJson = "application/json; charset=utf-8";

int status_for(ErrorKind kind) {
  switch (kind) {
    case ErrorKind::Usage:
    case ErrorKind::Input: return 400;
    case ErrorKind::Numerical: return 422;
    default: return 500;
  }
}

// A refusal that is neither bad input nor a failure (409: busy).
struct HttpError : std::runtime_error {
  HttpError(int s, const std::string& message) : std::runtime_error(message), status(s) {}
  int status;
};

void reply_error(httplib::Response& res, int status, const std::string& message) {
  res.status = status;
  res.set_content(error_api_json(message), kJson);
}

// X-Session header, else the `session` query parameter, else "default".
std::string session_id(const httplib::Request& req) {
  std::string id = req.get_header_value("X-Session");
  if (id.empty() && req.has_param("session")) id = req.get_param_value("session");
  if (id.empty()) return "default";
  if (id.size() > 64) throw_usage("session id longer than 64 characters");
  for (const char c : id)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_')
      throw_usage("session id may hold letters, digits, '-' and '_' only");
  return id;
}

struct Body {
  std::string text;
  const char* type = kJson;
};

// Runs `answer` (which returns the body) and maps every failure to a status
// with {"error": message}: the server keeps serving whatever happens.
template <class Answer>
void reply(httplib::Response& res, Answer answer) {
  try {
    const Body body = answer();
    res.set_content(body.text, body.type);
  } catch (const HttpError& e) {
    reply_error(res, e.status, e.what());
  } catch (const Error& e) {
    reply_error(res, status_for(e.kind()), e.what());
  } catch (const nlohmann::json::exception& e) {
    reply_error(res, 400, e.what());
  } catch (const std::bad_alloc&) {
    reply_error(res, 500, "out of memory");
  } catch (const std::exception& e) {
    reply_error(res, 500, std::string("internal error: ") + e.what());
  }
}

// `?uv=binary`: the UVs as raw little-endian float64 (the body) and the rest
// of the answer as JSON in the X-Answer header (what the page uses);
// `?uv=float32`: likewise as float32 (half the bytes, while dragging).
Body handle_solve(ServeState& s, const httplib::Request& req, httplib::Response& res) {
  bool binary = false, float32 = false;
  if (req.has_param("uv")) {
    const std::string format = req.get_param_value("uv");
    if (format != "binary" && format != "float32") throw_usage("uv: the formats are binary and float32");
    binary = true;
    float32 = format == "float32";
  }
  const SolveRequest request = parse_solve_request(req.body, s.mesh, s.data.F);
  const std::shared_ptr<Session> session = s.sessions->get(session_id(req));
  SolveAnswer answer;
  {
    std::lock_guard<std::mutex> lock(session->mutex);
    answer = session->state.solve(request);
  }
  if (!binary) return {solve_api_json(s.mesh, s.frames, answer)};
  res.set_header("X-Answer", solve_api_header(s.mesh, s.frames, answer, float32));
  return {uv_binary(answer.uv, float32), "application/octet-stream"};
}

// The starting boundary of the optimization endpoints: the request's circle
// or square, or, with moves, the session's boundary after them (given
// positions in output coordinates, used exactly).
ParamOptions start_options(Session& session, const SolveRequest& r) {
  ParamOptions o;
  o.weights = r.weights;
  o.boundary = r.boundary == BoundaryShape::Square ? BoundaryShape::Square : BoundaryShape::Circle;
  if (!r.moves.empty()) {
    std::lock_guard<std::mutex> lock(session.mutex);
    o.given = session.state.boundary_after(r);
    o.boundary = BoundaryShape::Given;
  }
  return o;
}

// Paper section 5.1: the blend lambda U_conformal + (1 - lambda) U_authalic
// minimising the energy; the answer's map is that blend (not the mixed map).
Body handle_optimal_lambda(ServeState& s, const httplib::Request& req) {
  const OptimalLambdaRequest q = parse_optimal_lambda_request(req.body, s.mesh, s.data.F);
  const std::shared_ptr<Session> session = s.sessions->get(session_id(req));
  OptimalLambdaOptions o;
  o.base = start_options(*session, q.solve);
  o.energy = q.energy;
  const OptimalLambdaResult r = optimal_lambda(s.mesh, o);
  SolveAnswer a;
  a.uv = r.map.UV;
  a.update_ms = r.conformal_ms + r.authalic_ms + r.polynomial_ms;
  a.path = "blend";
  a.factorizations = r.map.factorizations;
  return {solve_api_json(s.mesh, s.frames, a,
                         {{"lambda", r.lambda},
                          {"energy", r.energy},
                          {"energy_at_0", r.energy_at_0},
                          {"energy_at_1", r.energy_at_1},
                          {"coefficients", r.coefficients},
                          {"boundary_scale", r.boundary_scale}})};
}

// Paper section 5.2. Holds this request's thread until done; meanwhile
// GET /api/optimize_boundary/progress reads the energies so far.
Body handle_optimize_boundary(ServeState& s, const httplib::Request& req) {
  const OptimizeBoundaryRequest q = parse_optimize_boundary_request(req.body, s.mesh, s.data.F);
  const std::shared_ptr<Session> session = s.sessions->get(session_id(req));
  OptimizeProgress& progress = session->progress;
  {
    std::lock_guard<std::mutex> lock(progress.mutex);
    if (progress.running) throw HttpError(409, "a boundary optimization is already running in this session");
    progress.running = true;
    progress.energies.clear();
  }
  struct Done {
    OptimizeProgress& p;
    ~Done() { std::lock_guard<std::mutex> lock(p.mutex); p.running = false; }
  } done{progress};
  BoundaryOptimizationOptions o;
  o.base = start_options(*session, q.solve);
  o.energy = q.energy;
  o.max_iterations = q.max_iterations;
  o.progress = [&progress](int, double energy) {
    std::lock_guard<std::mutex> lock(progress.mutex);
    progress.energies.push_back(energy);
  };
  const BoundaryOptimizationResult r = optimize_boundary(s.mesh, o);
  SolveAnswer a;
  a.uv = r.map.UV;
  a.update_ms = r.setup_ms + r.optimize_ms;
  a.path = "optimize";
  a.factorizations = r.factorizations;
  return {solve_api_json(s.mesh, s.frames, a,
                         {{"energy_history", r.energy_history},
                          {"iterations", r.iterations},
                          {"stop_reason", r.stop_reason},
                          {"flipped_initial", r.flipped_initial},
                          {"flipped_final", r.flipped_final},
                          {"setup_ms", r.setup_ms},
                          {"optimize_ms", r.optimize_ms}})};
}

Body handle_progress(ServeState& s, const httplib::Request& req) {
  const std::shared_ptr<Session> session = s.sessions->get(session_id(req));
  std::lock_guard<std::mutex> lock(session->progress.mutex);
  return {nlohmann::json{{"running", session->progress.running}, {"energies", session->progress.energies}}.dump()};
}

RequestFacts facts_of(const httplib::Request& req) {
  RequestFacts f;
  f.method = req.method;
  f.path = req.path;
  f.host = req.get_header_value("Host");
  f.host_count = req.get_header_value_count("Host");
  f.origin = req.get_header_value("Origin");
  f.fetch_site = req.get_header_value("Sec-Fetch-Site");
  f.cookie = req.get_header_value("Cookie");
  f.token_header = req.get_header_value(kTokenHeader);
  if (req.has_param("token")) f.token_query = req.get_param_value("token");
  f.has_content_length = req.has_header("Content-Length");
  f.has_transfer_encoding = req.has_header("Transfer-Encoding");
  return f;
}

// Runs before routing, so before a body is read. A refused request's body
// stays unread: "Connection: close" makes the client drop the connection
// rather than send its next request after those bytes. No CORS header is
// ever sent, so browsers keep other sites' pages from reading any answer.
void add_guard(httplib::Server& server, const ServeState& s) {
  server.set_pre_routing_handler([&s](const httplib::Request& req, httplib::Response& res) {
    const Verdict v = check_request(s.hosts, s.token, facts_of(req));
    if (v.refusal == Refusal::None) {
      if (v.set_cookie) res.set_header("Set-Cookie", token_cookie(s.token, s.hosts.port));
      return httplib::Server::HandlerResponse::Unhandled;
    }
    res.status = refusal_status(v.refusal);
    res.set_content(refusal_message(v.refusal) + "\n", "text/plain; charset=utf-8");
    res.set_header("Connection", "close");
    return httplib::Server::HandlerResponse::Handled;
  });
}

void add_routes(httplib::Server& server, ServeState& s) {
  server.Get("/", [](const httplib::Request&, httplib::Response& res) {
    res.set_content(web::index_html, "text/html; charset=utf-8");
  });
  for (const web::Asset& asset : web::assets) {
    if (std::string(asset.name) == "index.html") continue;
    server.Get("/" + std::string(asset.name), [&asset](const httplib::Request&, httplib::Response& res) {
      res.set_content(asset.content, asset.type);
    });
  }
  server.Get("/api/mesh", [&s](const httplib::Request&, httplib::Response& res) {
    res.set_content(s.mesh_json, kJson);
  });
  server.Post("/api/solve", [&s](const httplib::Request& req, httplib::Response& res) {
    reply(res, [&] { return handle_solve(s, req, res); });
  });
  server.Post("/api/optimal_lambda", [&s](const httplib::Request& req, httplib::Response& res) {
    reply(res, [&] { return handle_optimal_lambda(s, req); });
  });
  server.Post("/api/optimize_boundary", [&s](const httplib::Request& req, httplib::Response& res) {
    reply(res, [&] { return handle_optimize_boundary(s, req); });
  });
  server.Get("/api/optimize_boundary/progress", [&s](const httplib::Request& req, httplib::Response& res) {
    reply(res, [&] { return handle_progress(s, req); });
  });
  server.set_exception_handler([](const httplib::Request&, httplib::Response& res, std::exception_ptr) {
    reply_error(res, 500, "internal error");
  });
  server.set_error_handler([](const httplib::Request&, httplib::Response& res) {
    if (res.body.empty()) {
      const int status = res.status;
      reply_error(res, status, status == 413 ? "request body too large" : "HTTP " + std::to_string(status));
    }
  });
}

int run_serve(const ServeArgs& a) {
  if (a.max_sessions < 1) throw_usage("--max-sessions must be at least 1");
  if (!(a.max_body_mib > 0)) throw_usage("--max-body must be positive");
  if (a.port < 0 || a.port > 65535) throw_usage("--port must be in 0..65535");
  ServeState s;
  ReadOptions ro;
  ro.max_vertices = a.max_vertices;
  ro.max_faces = faces_for_vertices(a.max_vertices);
  s.data = read_mesh(a.input, ro);
  s.mesh = make_mesh(s.data);
  s.mesh_json = mesh_api_json(s.mesh, s.data.F);
  s.frames = face_frames(s.mesh.V, s.mesh.F);
  s.sessions = std::make_unique<SessionStore>(s.mesh, static_cast<size_t>(a.max_sessions));

  httplib::Server server;
  server.set_payload_max_length(static_cast<size_t>(a.max_body_mib * 1024 * 1024));
  // A drag is a stream of small requests on one kept-alive connection. With
  // Nagle's algorithm on, the answer's last segment waits for the client's
  // delayed ACK (tens of ms per request); and cpp-httplib closes a kept-alive
  // connection after 5 requests by default, so every fifth move paid a new
  // TCP connection. Idle connections still close after the 5 s timeout, so
  // they do not hold the worker threads.
  server.set_tcp_nodelay(true);
  server.set_keep_alive_max_count(100000);
  add_routes(server, s);
  const int port = a.port == 0 ? server.bind_to_any_port(a.host) : (server.bind_to_port(a.host, a.port) ? a.port : -1);
  if (port < 0) throw_usage("cannot listen on " + a.host + ":" + std::to_string(a.port));
  const bool wildcard = is_wildcard_address(a.host);
  s.hosts = host_policy(a.host, port, wildcard ? machine_addresses() : std::vector<std::string>());
  s.token = random_token();
  add_guard(server, s);
  if (wildcard)
    std::cerr << "intrinsic serve: warning: listening on " << a.host
              << ": the editor is reachable from the network (by this machine's addresses and name, with the token)"
              << std::endl;
  // A wildcard address is no place to browse to: the URL names this machine.
  const std::string url_host = wildcard ? "127.0.0.1" : (a.host.find(':') != std::string::npos ? "[" + a.host + "]" : a.host);
  std::cout << "intrinsic serve: " << a.input << " (" << s.mesh.V.rows() << " vertices) at http://" << url_host << ":"
            << port << "/?token=" << s.token << std::endl;
  if (!server.listen_after_bind()) throw_usage("server stopped listening");
  return 0;
}

}  // namespace

void register_serve(CLI::App& app, Runner& run) {
  auto a = std::make_shared<ServeArgs>();
  CLI::App* cmd = app.add_subcommand("serve", "Interactive editor in the browser: a local web server");
  cmd->add_option("input", a->input, "Input mesh (.obj, .off, .ply, .stl, optionally .gz)")->required();
  cmd->add_option("--port", a->port, "Port (0: any free port)")->capture_default_str();
  cmd->add_option("--host", a->host, "Address to bind (127.0.0.1: this machine only; 0.0.0.0: the network, with a warning)")
      ->capture_default_str();
  cmd->add_option("--max-sessions", a->max_sessions, "Sessions kept (least recently used dropped)")
      ->capture_default_str();
  cmd->add_option("--max-body", a->max_body_mib, "Largest request body in MiB (larger: HTTP 413)")
      ->capture_default_str();
  cmd->add_option("--max-vertices", a->max_vertices, "Refuse inputs with more vertices")->capture_default_str();
  cmd->callback([&run, a] { run = [a] { return run_serve(*a); }; });
}

}  // namespace intrinsic::app
