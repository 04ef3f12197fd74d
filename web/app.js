// The editor page's code (served by `intrinsic serve`, embedded with
// index.html): loads the mesh from /api/mesh, asks /api/solve for maps, draws
// the surface with a checkerboard (hand-written WebGL) and the layout (2D
// canvas), and turns drags of boundary vertices or pins into requests, with
// at most one request in flight (the newest waiting one is sent next).
// window.__intrinsic exposes the state for the browser test.
'use strict';

const session = Array.from(crypto.getRandomValues(new Uint8Array(12)), (b) => b.toString(16).padStart(2, '0')).join('');
const $ = (id) => document.getElementById(id);
const state = {
  mesh: null, uv: null, answer: null, moves: new Map(), pins: null,
  dragging: null, inFlight: false, queued: null, lastRequest: null, updates: 0, frames: 0, error: null,
};
window.__intrinsic = { session, state, handles: () => handles(), request: () => requestBody() };

// ---- requests -------------------------------------------------------------

function requestBody() {
  const body = { method: $('method').value, boundary: $('boundary').value };
  if (body.method === 'mixed') {
    const lambda = Number($('lambda').value);
    body.lambda = lambda;
    body.mu = 1 - lambda;
  }
  if (body.boundary === 'natural') {
    if (state.pins) body.pins = state.pins.map((p) => [p[0], p[1], p[2]]);
  } else if (state.moves.size) {
    body.moves = Array.from(state.moves, ([v, uv]) => [v, uv[0], uv[1]]);
  }
  return body;
}

// Sends now, or queues (replacing an older queued body) when one is in flight.
function solve() {
  const body = requestBody();
  if (state.inFlight) { state.queued = body; return; }
  send(body);
}

async function send(body) {
  state.inFlight = true;
  state.lastRequest = body;
  const t0 = performance.now();
  try {
    const res = await fetch('/api/solve', {
      method: 'POST', headers: { 'Content-Type': 'application/json', 'X-Session': session }, body: JSON.stringify(body),
    });
    const answer = await res.json();
    if (!res.ok) throw new Error(answer.error || ('HTTP ' + res.status));
    receive(answer, performance.now() - t0);
    state.error = null;
    $('error').textContent = '';
  } catch (e) {
    state.error = String(e.message || e);
    $('error').textContent = state.error;
  } finally {
    state.inFlight = false;
    if (state.queued) { const next = state.queued; state.queued = null; send(next); }
  }
}

function receive(answer, roundTrip) {
  state.answer = answer;
  const n = state.mesh.vertices;
  const uv = new Float64Array(2 * n);
  answer.uv.forEach((p, i) => { uv[2 * i] = p[0]; uv[2 * i + 1] = p[1]; });
  state.uv = uv;
  if (answer.pins && !state.dragging) state.pins = answer.pins.map((p) => p.slice());
  $('flips').textContent = answer.flipped_triangles;
  $('angle').textContent = answer.angle_distortion_mean.toFixed(4);
  $('updateMs').textContent = answer.update_ms.toFixed(3);
  $('roundTrip').textContent = roundTrip.toFixed(1);
  $('path').textContent = answer.path;
  uploadUV();
  state.updates++;
  draw();
}

// ---- 3D view: WebGL --------------------------------------------------------

const gl3 = { gl: null, prog: null, buffers: {}, count: 0, yaw: 0.6, pitch: 0.4, dist: 2.5, center: [0, 0, 0], radius: 1 };

const VS = `attribute vec3 p; attribute vec3 n; attribute vec2 t; uniform mat4 mvp; uniform mat4 mv;
varying vec2 vt; varying vec3 vn; void main() { vt = t; vn = (mv * vec4(n, 0.0)).xyz; gl_Position = mvp * vec4(p, 1.0); }`;
const FS = `precision mediump float; varying vec2 vt; varying vec3 vn;
void main() { vec2 c = floor(vt * 16.0); float k = mod(c.x + c.y, 2.0);
  vec3 base = mix(vec3(0.95, 0.95, 0.92), vec3(0.2, 0.35, 0.7), k);
  float l = 0.35 + 0.65 * abs(normalize(vn).z); gl_FragColor = vec4(base * l, 1.0); }`;

function compile(gl, type, src) {
  const s = gl.createShader(type);
  gl.shaderSource(s, src);
  gl.compileShader(s);
  if (!gl.getShaderParameter(s, gl.COMPILE_STATUS)) throw new Error(gl.getShaderInfoLog(s));
  return s;
}

function init3d() {
  const canvas = $('view3d');
  const gl = canvas.getContext('webgl', { antialias: true, preserveDrawingBuffer: true });
  if (!gl) { $('error').textContent = 'WebGL is not available: 3D view disabled'; return; }
  if (!gl.getExtension('OES_element_index_uint') && state.mesh.vertices > 65535) {
    $('error').textContent = 'WebGL lacks 32-bit indices: 3D view disabled'; return;
  }
  const prog = gl.createProgram();
  gl.attachShader(prog, compile(gl, gl.VERTEX_SHADER, VS));
  gl.attachShader(prog, compile(gl, gl.FRAGMENT_SHADER, FS));
  gl.linkProgram(prog);
  gl3.gl = gl;
  gl3.prog = prog;
  const m = state.mesh;
  const pos = new Float32Array(m.positions);
  gl3.buffers.p = buffer(gl, gl.ARRAY_BUFFER, pos);
  gl3.buffers.n = buffer(gl, gl.ARRAY_BUFFER, vertexNormals(pos, m.triangles));
  gl3.buffers.t = buffer(gl, gl.ARRAY_BUFFER, new Float32Array(2 * m.vertices));
  gl3.buffers.i = buffer(gl, gl.ELEMENT_ARRAY_BUFFER, new Uint32Array(m.triangles));
  gl3.count = m.triangles.length;
  fitCamera(pos);
  orbitControls(canvas);
}

function buffer(gl, target, data) {
  const b = gl.createBuffer();
  gl.bindBuffer(target, b);
  gl.bufferData(target, data, target === gl.ARRAY_BUFFER ? gl.DYNAMIC_DRAW : gl.STATIC_DRAW);
  return b;
}

function vertexNormals(pos, tri) {
  const nrm = new Float32Array(pos.length);
  for (let f = 0; f < tri.length; f += 3) {
    const a = 3 * tri[f], b = 3 * tri[f + 1], c = 3 * tri[f + 2];
    const ux = pos[b] - pos[a], uy = pos[b + 1] - pos[a + 1], uz = pos[b + 2] - pos[a + 2];
    const vx = pos[c] - pos[a], vy = pos[c + 1] - pos[a + 1], vz = pos[c + 2] - pos[a + 2];
    const nx = uy * vz - uz * vy, ny = uz * vx - ux * vz, nz = ux * vy - uy * vx;
    for (const k of [a, b, c]) { nrm[k] += nx; nrm[k + 1] += ny; nrm[k + 2] += nz; }
  }
  return nrm;
}

function fitCamera(pos) {
  const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
  for (let i = 0; i < pos.length; i += 3)
    for (let k = 0; k < 3; k++) { lo[k] = Math.min(lo[k], pos[i + k]); hi[k] = Math.max(hi[k], pos[i + k]); }
  gl3.center = lo.map((l, k) => (l + hi[k]) / 2);
  gl3.radius = Math.max(1e-12, Math.hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]) / 2);
}

function orbitControls(canvas) {
  let last = null;
  canvas.addEventListener('mousedown', (e) => { last = [e.clientX, e.clientY]; });
  window.addEventListener('mouseup', () => { last = null; });
  window.addEventListener('mousemove', (e) => {
    if (!last) return;
    gl3.yaw += (e.clientX - last[0]) * 0.01;
    gl3.pitch = Math.max(-1.5, Math.min(1.5, gl3.pitch + (e.clientY - last[1]) * 0.01));
    last = [e.clientX, e.clientY];
    draw();
  });
  canvas.addEventListener('wheel', (e) => {
    e.preventDefault();
    gl3.dist = Math.max(0.2, Math.min(50, gl3.dist * Math.exp(e.deltaY * 0.001)));
    draw();
  }, { passive: false });
}

function uploadUV() {
  if (!gl3.gl) return;
  const gl = gl3.gl;
  gl.bindBuffer(gl.ARRAY_BUFFER, gl3.buffers.t);
  gl.bufferSubData(gl.ARRAY_BUFFER, 0, new Float32Array(state.uv));
}

// Column-major 4x4 matrices.
function multiply(a, b) {
  const o = new Float32Array(16);
  for (let c = 0; c < 4; c++)
    for (let r = 0; r < 4; r++) {
      let s = 0;
      for (let k = 0; k < 4; k++) s += a[k * 4 + r] * b[c * 4 + k];
      o[c * 4 + r] = s;
    }
  return o;
}

function cameraMatrices(aspect) {
  const s = 1 / gl3.radius, [cx, cy, cz] = gl3.center;
  const cy_ = Math.cos(gl3.yaw), sy = Math.sin(gl3.yaw), cp = Math.cos(gl3.pitch), sp = Math.sin(gl3.pitch);
  const rotY = [cy_, 0, -sy, 0, 0, 1, 0, 0, sy, 0, cy_, 0, 0, 0, 0, 1];
  const rotX = [1, 0, 0, 0, 0, cp, sp, 0, 0, -sp, cp, 0, 0, 0, 0, 1];
  const model = [s, 0, 0, 0, 0, s, 0, 0, 0, 0, s, 0, -cx * s, -cy * s, -cz * s, 1];
  const view = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, -gl3.dist, 1];
  const mv = multiply(view, multiply(rotX, multiply(rotY, model)));
  const f = 1 / Math.tan(0.4), near = 0.05, far = 100;
  const proj = [f / aspect, 0, 0, 0, 0, f, 0, 0, 0, 0, (far + near) / (near - far), -1, 0, 0, 2 * far * near / (near - far), 0];
  return { mv, mvp: multiply(proj, mv) };
}

function draw3d() {
  const gl = gl3.gl;
  if (!gl) return;
  const canvas = gl.canvas;
  resize(canvas);
  gl.viewport(0, 0, canvas.width, canvas.height);
  gl.clearColor(1, 1, 1, 1);
  gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
  gl.enable(gl.DEPTH_TEST);
  gl.useProgram(gl3.prog);
  for (const [name, size] of [['p', 3], ['n', 3], ['t', 2]]) {
    const loc = gl.getAttribLocation(gl3.prog, name);
    gl.bindBuffer(gl.ARRAY_BUFFER, gl3.buffers[name]);
    gl.enableVertexAttribArray(loc);
    gl.vertexAttribPointer(loc, size, gl.FLOAT, false, 0, 0);
  }
  const { mv, mvp } = cameraMatrices(canvas.width / canvas.height);
  gl.uniformMatrix4fv(gl.getUniformLocation(gl3.prog, 'mvp'), false, mvp);
  gl.uniformMatrix4fv(gl.getUniformLocation(gl3.prog, 'mv'), false, mv);
  gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, gl3.buffers.i);
  gl.drawElements(gl.TRIANGLES, gl3.count, gl.UNSIGNED_INT, 0);
}

function resize(canvas) {
  const dpr = window.devicePixelRatio || 1;
  const w = Math.round(canvas.clientWidth * dpr), h = Math.round(canvas.clientHeight * dpr);
  if (canvas.width !== w || canvas.height !== h) { canvas.width = w; canvas.height = h; }
}

// ---- 2D view ---------------------------------------------------------------

// The layout window: [-0.15, 1.15]^2 (maps come out in [0, 1]^2), fixed so a
// dragged vertex stays under the mouse.
function view2d() {
  const c = $('view2d'), w = c.clientWidth, h = c.clientHeight;
  const side = Math.min(w, h) / 1.3;
  return { ox: (w - 1.3 * side) / 2 + 0.15 * side, oy: (h + 1.3 * side) / 2 - 0.15 * side, side };
}
const toScreen = (v, u, w) => [v.ox + u * v.side, v.oy - w * v.side];
const toUV = (v, x, y) => [(x - v.ox) / v.side, (v.oy - y) / v.side];

// Draggable points in CSS pixels relative to the page: boundary vertices of
// the outer loop (fixed boundary) or the pins (natural map).
function handles() {
  if (!state.uv) return [];
  const v = view2d(), rect = $('view2d').getBoundingClientRect();
  const list = $('boundary').value === 'natural' ? (state.pins || []).map((p) => p[0]) : state.mesh.boundary_loops[0];
  return list.map((vertex) => {
    const [x, y] = toScreen(v, state.uv[2 * vertex], state.uv[2 * vertex + 1]);
    return { vertex, x: rect.left + window.scrollX + x, y: rect.top + window.scrollY + y };
  });
}

function draw2d() {
  const c = $('view2d');
  resize(c);
  const ctx = c.getContext('2d'), dpr = window.devicePixelRatio || 1, v = view2d();
  ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
  ctx.clearRect(0, 0, c.clientWidth, c.clientHeight);
  if (!state.uv) return;
  const uv = state.uv, tri = state.mesh.triangles, edges = new Path2D(), flipped = new Path2D();
  for (let f = 0; f < tri.length; f += 3) {
    const a = toScreen(v, uv[2 * tri[f]], uv[2 * tri[f] + 1]);
    const b = toScreen(v, uv[2 * tri[f + 1]], uv[2 * tri[f + 1] + 1]);
    const d = toScreen(v, uv[2 * tri[f + 2]], uv[2 * tri[f + 2] + 1]);
    const target = (b[0] - a[0]) * (d[1] - a[1]) - (b[1] - a[1]) * (d[0] - a[0]) > 0 ? flipped : edges;
    target.moveTo(a[0], a[1]); target.lineTo(b[0], b[1]); target.lineTo(d[0], d[1]); target.closePath();
  }
  ctx.lineWidth = 0.5;
  ctx.strokeStyle = '#8896aa';
  ctx.stroke(edges);
  ctx.fillStyle = 'rgba(220, 0, 0, 0.6)';
  ctx.fill(flipped);
  ctx.lineWidth = 1.5;
  ctx.strokeStyle = '#222';
  for (const loop of state.mesh.boundary_loops) {
    ctx.beginPath();
    loop.forEach((i, k) => { const p = toScreen(v, uv[2 * i], uv[2 * i + 1]); k ? ctx.lineTo(p[0], p[1]) : ctx.moveTo(p[0], p[1]); });
    ctx.closePath();
    ctx.stroke();
  }
  drawHandles(ctx, v);
}

function drawHandles(ctx, v) {
  const natural = $('boundary').value === 'natural';
  const list = natural ? (state.pins || []).map((p) => p[0]) : state.mesh.boundary_loops[0];
  for (const i of list) {
    const p = toScreen(v, state.uv[2 * i], state.uv[2 * i + 1]);
    const moved = natural || state.moves.has(i);
    ctx.fillStyle = moved ? '#e07000' : '#1f5fbf';
    ctx.beginPath();
    ctx.arc(p[0], p[1], natural ? 6 : moved ? 4 : 2, 0, 2 * Math.PI);
    ctx.fill();
  }
}

function nearestHandle(x, y) {
  let best = null, bestD = 8;  // pixels
  for (const h of handles()) {
    const d = Math.hypot(h.x - x, h.y - y);
    if (d < bestD) { best = h; bestD = d; }
  }
  return best;
}

function dragControls() {
  const c = $('view2d');
  c.addEventListener('mousedown', (e) => {
    const h = nearestHandle(e.pageX, e.pageY);
    if (h) { state.dragging = h.vertex; e.preventDefault(); }
  });
  window.addEventListener('mousemove', (e) => {
    if (state.dragging === null) return;
    const rect = c.getBoundingClientRect();
    moveHandle(state.dragging, toUV(view2d(), e.clientX - rect.left, e.clientY - rect.top));
  });
  window.addEventListener('mouseup', () => { state.dragging = null; });
}

function moveHandle(vertex, uv) {
  if ($('boundary').value === 'natural') {
    const pin = state.pins.find((p) => p[0] === vertex);
    pin[1] = uv[0];
    pin[2] = uv[1];
  } else {
    state.moves.set(vertex, uv);
  }
  solve();
}

// ---- page ------------------------------------------------------------------

let frameRequested = false;
function draw() {
  if (frameRequested) return;
  frameRequested = true;
  requestAnimationFrame(() => { frameRequested = false; draw3d(); draw2d(); state.frames++; });
}

function downloadObj() {
  const m = state.mesh, uv = state.uv, lines = ['# intrinsic serve: ' + $('method').value + ', ' + $('boundary').value];
  for (let i = 0; i < m.vertices; i++) lines.push('v ' + m.positions.slice(3 * i, 3 * i + 3).join(' '));
  for (let i = 0; i < m.vertices; i++) lines.push('vt ' + uv[2 * i] + ' ' + uv[2 * i + 1]);
  for (let f = 0; f < m.triangles.length; f += 3) {
    const a = m.triangles[f] + 1, b = m.triangles[f + 1] + 1, c = m.triangles[f + 2] + 1;
    lines.push(`f ${a}/${a} ${b}/${b} ${c}/${c}`);
  }
  const link = document.createElement('a');
  link.href = URL.createObjectURL(new Blob([lines.join('\n') + '\n'], { type: 'text/plain' }));
  link.download = 'intrinsic.obj';
  link.click();
  URL.revokeObjectURL(link.href);
}

function controls() {
  const optionsChanged = () => {
    state.moves.clear();
    state.pins = null;
    $('lambdaBox').style.display = $('method').value === 'mixed' ? '' : 'none';
    solve();
  };
  $('method').addEventListener('change', optionsChanged);
  $('boundary').addEventListener('change', optionsChanged);
  $('reset').addEventListener('click', optionsChanged);
  $('lambda').addEventListener('input', () => { $('lambdaValue').textContent = Number($('lambda').value).toFixed(2); });
  $('lambda').addEventListener('change', solve);
  $('download').addEventListener('click', downloadObj);
  window.addEventListener('resize', draw);
  $('lambdaBox').style.display = 'none';
}

async function main() {
  const res = await fetch('/api/mesh');
  state.mesh = await res.json();
  $('meshInfo').textContent = `${state.mesh.vertices} vertices, ${state.mesh.faces} faces`;
  controls();
  try { init3d(); } catch (e) { $('error').textContent = 'WebGL: ' + e.message; }
  dragControls();
  solve();
}

main();
