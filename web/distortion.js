// Per-triangle distortion of the current layout for the 2D view's colouring,
// computed in the page so a drag costs no extra request (the same measures
// as the library's face_distortion, docs/maths.md §9): with s1 >= s2 the
// singular values of the triangle's Jacobian, angle = s1 / s2 and area =
// max(r, 1/r) with r = s1 s2 after scaling the whole layout to the surface's
// area. Flipped triangles use |J| as the library does.
export function faceDistortion(mesh, uv, kind) {
  const tri = mesh.triangles, pos = mesh.positions, m = tri.length / 3;
  const out = new Float64Array(m);
  let area3 = 0, areaUV = 0;
  if (kind === 'area') {
    for (let f = 0; f < m; f++) {
      const [a3, aUV] = areas(pos, uv, tri[3 * f], tri[3 * f + 1], tri[3 * f + 2]);
      area3 += a3;
      areaUV += aUV;
    }
  }
  const k = areaUV !== 0 ? area3 / Math.abs(areaUV) : 1;
  for (let f = 0; f < m; f++) {
    const s = singularValues(pos, uv, tri[3 * f], tri[3 * f + 1], tri[3 * f + 2]);
    if (kind === 'angle') out[f] = s[1] > 0 ? s[0] / s[1] : Infinity;
    else { const r = s[0] * s[1] * k; out[f] = r > 0 ? Math.max(r, 1 / r) : Infinity; }
  }
  return out;
}

function areas(pos, uv, a, b, c) {
  const e1 = [pos[3 * b] - pos[3 * a], pos[3 * b + 1] - pos[3 * a + 1], pos[3 * b + 2] - pos[3 * a + 2]];
  const e2 = [pos[3 * c] - pos[3 * a], pos[3 * c + 1] - pos[3 * a + 1], pos[3 * c + 2] - pos[3 * a + 2]];
  const cx = e1[1] * e2[2] - e1[2] * e2[1], cy = e1[2] * e2[0] - e1[0] * e2[2], cz = e1[0] * e2[1] - e1[1] * e2[0];
  const p1 = [uv[2 * b] - uv[2 * a], uv[2 * b + 1] - uv[2 * a + 1]], p2 = [uv[2 * c] - uv[2 * a], uv[2 * c + 1] - uv[2 * a + 1]];
  return [Math.hypot(cx, cy, cz) / 2, (p1[0] * p2[1] - p1[1] * p2[0]) / 2];
}

// Singular values [s1, s2] of J = [p1 p2] [q1 q2]^-1, q the triangle in its own 2D frame.
function singularValues(pos, uv, a, b, c) {
  const e1 = [pos[3 * b] - pos[3 * a], pos[3 * b + 1] - pos[3 * a + 1], pos[3 * b + 2] - pos[3 * a + 2]];
  const e2 = [pos[3 * c] - pos[3 * a], pos[3 * c + 1] - pos[3 * a + 1], pos[3 * c + 2] - pos[3 * a + 2]];
  const l1 = Math.hypot(e1[0], e1[1], e1[2]);
  const cx = e1[1] * e2[2] - e1[2] * e2[1], cy = e1[2] * e2[0] - e1[0] * e2[2], cz = e1[0] * e2[1] - e1[1] * e2[0];
  const q2x = (e1[0] * e2[0] + e1[1] * e2[1] + e1[2] * e2[2]) / l1, q2y = Math.hypot(cx, cy, cz) / l1;
  if (!(l1 > 0) || !(q2y > 0)) return [Infinity, 0];
  const p1x = uv[2 * b] - uv[2 * a], p1y = uv[2 * b + 1] - uv[2 * a + 1];
  const p2x = uv[2 * c] - uv[2 * a], p2y = uv[2 * c + 1] - uv[2 * a + 1];
  // Q = [[l1, q2x], [0, q2y]], Q^-1 = [[1/l1, -q2x/(l1 q2y)], [0, 1/q2y]].
  const ja = p1x / l1, jc = p1y / l1;
  const jb = (p2x - ja * q2x) / q2y, jd = (p2y - jc * q2x) / q2y;
  const E = (ja + jd) / 2, F = (ja - jd) / 2, G = (jc + jb) / 2, H = (jc - jb) / 2;
  const Q = Math.hypot(E, H), R = Math.hypot(F, G);
  return [Q + R, Math.abs(Q - R)];
}

// Colour of value v >= 1 on a logarithmic scale from 1 (white) to vmax (dark red).
const STOPS = [[255, 255, 255], [255, 230, 120], [250, 150, 40], [210, 40, 30], [110, 0, 20]];
export function rgbOf(t) {
  const x = Math.max(0, Math.min(1, t)) * (STOPS.length - 1), i = Math.min(STOPS.length - 2, Math.floor(x)), f = x - i;
  return STOPS[i].map((s, k) => Math.round(s + f * (STOPS[i + 1][k] - s)));
}
export function colourOf(t) {
  const c = rgbOf(t);
  return `rgb(${c[0]}, ${c[1]}, ${c[2]})`;
}
export const scaleOf = (v, vmax) => (v >= vmax || !isFinite(v) ? 1 : Math.log(Math.max(1, v)) / Math.log(vmax));
