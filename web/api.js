// Requests to the server's API (docs/cli.md "intrinsic serve"): the solve queue
// with at most one /api/solve in flight (the newest waiting body is sent
// next), and plain JSON posts for the other endpoints.
import { $, natural, session, state } from './state.js';
import { draw } from './view.js';

export function hasConstraints() {
  return state.constraints.points.length > 0 || state.constraints.lines.length > 0;
}

export function requestBody(method = $('method').value) {
  const body = { method, boundary: $('boundary').value };
  if (method === 'mixed') {
    const lambda = Number($('lambda').value);
    body.lambda = lambda;
    body.mu = 1 - lambda;
  }
  if (natural()) {
    if (state.pins) body.pins = state.pins.map((p) => [p[0], p[1], p[2]]);
  } else if (state.moves.size) {
    body.moves = Array.from(state.moves, ([v, uv]) => [v, uv[0], uv[1]]);
  }
  if (hasConstraints()) body.constraints = JSON.parse(JSON.stringify(state.constraints));
  return body;
}

// The API's refusals are {"error": message}; the server's guard answers in
// plain text (a wrong or missing token: the server was restarted, so its URL
// changed; see docs/cli.md "intrinsic serve"). The same-origin fetches carry the
// token in the cookie the page's first load got.
export async function failure(res) {
  const text = await res.text();
  try { return new Error(JSON.parse(text).error || ('HTTP ' + res.status)); } catch (e) {
    return new Error(`HTTP ${res.status}: ${text.trim()}`);
  }
}

export async function post(route, body, sessionId = session) {
  const res = await fetch(route, {
    method: 'POST', headers: { 'Content-Type': 'application/json', 'X-Session': sessionId }, body: JSON.stringify(body),
  });
  if (!res.ok) throw await failure(res);
  return res.json();
}

// /api/solve?uv=binary: the UVs as raw float64 (little-endian, as every
// platform this runs on), the rest of the answer in the X-Answer header.
// While a drag is under way ?uv=float32 (half the bytes, what WebGL draws
// anyway); the release asks once more for the exact float64 answer.
async function postSolve(body, float32) {
  const res = await fetch(float32 ? '/api/solve?uv=float32' : '/api/solve?uv=binary', {
    method: 'POST', headers: { 'Content-Type': 'application/json', 'X-Session': session }, body: JSON.stringify(body),
  });
  if (!res.ok) throw await failure(res);
  const headersAt = performance.now();
  const answer = JSON.parse(res.headers.get('X-Answer'));
  const bytes = await res.arrayBuffer();
  answer.uvFlat = float32 ? new Float32Array(bytes) : new Float64Array(bytes);
  answer.bodyMs = performance.now() - headersAt;  // the UVs' transfer and copy into a typed array
  return answer;
}

// Sends now, or queues (replacing an older queued body) when one is in
// flight. `stamp`: the time of the mouse event that asked for it.
export function solve(stamp = null, onError = null) {
  const item = { body: requestBody(), stamp, onError, float32: state.dragging !== null };
  if (state.inFlight) { state.queued = item; return; }
  send(item);
}

async function send(item) {
  state.inFlight = true;
  state.lastRequest = item.body;
  const t0 = performance.now();
  try {
    const answer = await postSolve(item.body, item.float32);
    const roundTrip = performance.now() - t0;
    state.roundTrips.push(roundTrip);
    // Where a drag step's time goes (drag_bench.mjs): waiting to be sent
    // (one request in flight), request to headers (network and server), the
    // body, and the server's own update.
    state.phases.push({ wait: item.stamp === null ? 0 : t0 - item.stamp, headers: roundTrip - answer.bodyMs,
      body: answer.bodyMs, server: answer.update_ms });
    state.preview = null;
    show(answer, performance.now() - t0, item.stamp);
    setError(null);
  } catch (e) {
    setError(e);
    if (item.onError) item.onError(e);
  } finally {
    state.inFlight = false;
    if (state.queued) { const next = state.queued; state.queued = null; send(next); }
  }
}

export function setError(e) {
  state.error = e ? String(e.message || e) : null;
  $('error').textContent = state.error || '';
}

// Draws an answer of any endpoint (uv pairs, or uvFlat from postSolve: float64,
// or float32 while dragging; figures) and updates the panel.
export function show(answer, roundTrip, stamp = null) {
  state.answer = answer;
  if (answer.uvFlat) {
    state.uv = answer.uvFlat;
  } else {
    const uv = new Float64Array(2 * state.mesh.vertices);
    answer.uv.forEach((p, i) => { uv[2 * i] = p[0]; uv[2 * i + 1] = p[1]; });
    state.uv = uv;
  }
  if (answer.pins && !state.dragging) state.pins = answer.pins.map((p) => p.slice());
  $('flips').textContent = answer.flipped_triangles;
  // Answers while dragging (float32) carry the flips only; the exact answer
  // on release brings the means.
  if (answer.angle_distortion_mean !== undefined) {
    $('angle').textContent = answer.angle_distortion_mean.toFixed(4);
    $('area').textContent = answer.area_distortion_mean.toFixed(4);
  }
  $('updateMs').textContent = answer.update_ms.toFixed(3);
  $('roundTrip').textContent = roundTrip === null ? '-' : roundTrip.toFixed(1);
  $('path').textContent = answer.path;
  $('factorizations').textContent = answer.factorizations;
  state.updates++;
  draw(stamp);
}
