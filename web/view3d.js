// The 3D view: the surface with a checkerboard through the current UVs
// (hand-written WebGL), orbit and zoom, and picking a surface point under
// the mouse (for constraints: face and barycentric coordinates).
import { $, state } from './state.js';
import { draw } from './view.js';
import { program } from './gl.js';

export const gl3 = { gl: null, prog: null, buffers: {}, count: 0, yaw: 0.6, pitch: 0.4, dist: 2.5, center: [0, 0, 0], radius: 1 };

const VS = `attribute vec3 p; attribute vec3 n; attribute vec2 t; uniform mat4 mvp; uniform mat4 mv;
varying vec2 vt; varying vec3 vn; void main() { vt = t; vn = (mv * vec4(n, 0.0)).xyz; gl_Position = mvp * vec4(p, 1.0); }`;
const FS = `precision mediump float; varying vec2 vt; varying vec3 vn;
void main() { vec2 c = floor(vt * 16.0); float k = mod(c.x + c.y, 2.0);
  vec3 base = mix(vec3(0.95, 0.95, 0.92), vec3(0.2, 0.35, 0.7), k);
  float l = 0.35 + 0.65 * abs(normalize(vn).z); gl_FragColor = vec4(base * l, 1.0); }`;

export function init3d(onClick) {
  const canvas = $('view3d');
  const gl = canvas.getContext('webgl', { antialias: true, preserveDrawingBuffer: true });
  if (!gl) { $('error').textContent = 'WebGL is not available: 3D view disabled'; return; }
  if (!gl.getExtension('OES_element_index_uint') && state.mesh.vertices > 65535) {
    $('error').textContent = 'WebGL lacks 32-bit indices: 3D view disabled'; return;
  }
  const prog = program(gl, VS, FS);
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
  orbitControls(canvas, onClick);
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

// Drag: orbit. A click (the mouse moved less than 3 pixels) goes to onClick.
function orbitControls(canvas, onClick) {
  let last = null, down = null;
  canvas.addEventListener('mousedown', (e) => { last = [e.clientX, e.clientY]; down = last; });
  window.addEventListener('mouseup', (e) => {
    if (down && Math.hypot(e.clientX - down[0], e.clientY - down[1]) < 3) onClick(e);
    last = down = null;
  });
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

// New UVs (float32, 2n) into the texture-coordinate buffer only: the
// positions, normals and triangles never change.
export function uploadUV(uv32) {
  if (!gl3.gl) return;
  const gl = gl3.gl;
  gl.bindBuffer(gl.ARRAY_BUFFER, gl3.buffers.t);
  gl.bufferSubData(gl.ARRAY_BUFFER, 0, uv32);
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

export function cameraMatrices(aspect) {
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

export function draw3d() {
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

export function resize(canvas) {
  const dpr = window.devicePixelRatio || 1;
  const w = Math.round(canvas.clientWidth * dpr), h = Math.round(canvas.clientHeight * dpr);
  if (canvas.width !== w || canvas.height !== h) { canvas.width = w; canvas.height = h; }
}

// The surface point under client position (x, y): the nearest triangle whose
// projection holds the point, with perspective-correct barycentrics over
// its corners as GET /api/mesh lists them. null when none.
export function pick(x, y) {
  const canvas = $('view3d'), rect = canvas.getBoundingClientRect();
  const px = 2 * (x - rect.left) / rect.width - 1, py = 1 - 2 * (y - rect.top) / rect.height;
  const { mvp } = cameraMatrices(canvas.width / canvas.height);
  const m = state.mesh, pos = m.positions, n = m.vertices;
  const sx = new Float64Array(n), sy = new Float64Array(n), sz = new Float64Array(n), sw = new Float64Array(n);
  for (let i = 0; i < n; i++) {
    const X = pos[3 * i], Y = pos[3 * i + 1], Z = pos[3 * i + 2];
    const w = mvp[3] * X + mvp[7] * Y + mvp[11] * Z + mvp[15];
    sw[i] = w;
    sx[i] = (mvp[0] * X + mvp[4] * Y + mvp[8] * Z + mvp[12]) / w;
    sy[i] = (mvp[1] * X + mvp[5] * Y + mvp[9] * Z + mvp[13]) / w;
    sz[i] = (mvp[2] * X + mvp[6] * Y + mvp[10] * Z + mvp[14]) / w;
  }
  let best = null, bestZ = Infinity;
  const tri = m.triangles;
  for (let f = 0; f < tri.length / 3; f++) {
    const a = tri[3 * f], b = tri[3 * f + 1], c = tri[3 * f + 2];
    if (sw[a] <= 0 || sw[b] <= 0 || sw[c] <= 0) continue;
    const d = (sx[b] - sx[a]) * (sy[c] - sy[a]) - (sx[c] - sx[a]) * (sy[b] - sy[a]);
    if (d === 0) continue;
    const l1 = ((px - sx[a]) * (sy[c] - sy[a]) - (sx[c] - sx[a]) * (py - sy[a])) / d;
    const l2 = ((sx[b] - sx[a]) * (py - sy[a]) - (px - sx[a]) * (sy[b] - sy[a])) / d;
    const l0 = 1 - l1 - l2;
    if (l0 < 0 || l1 < 0 || l2 < 0) continue;
    const z = l0 * sz[a] + l1 * sz[b] + l2 * sz[c];
    if (z < bestZ) { bestZ = z; best = { face: f, screen: [l0, l1, l2], w: [sw[a], sw[b], sw[c]] }; }
  }
  if (!best) return null;
  const q = best.screen.map((l, k) => l / best.w[k]), s = q[0] + q[1] + q[2];
  return { face: best.face, bary: q.map((v) => v / s) };
}
