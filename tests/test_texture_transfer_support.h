// What the texture-transfer tests read back from the files the product
// writes, independently of the library's glTF code: tinygltf loads the
// document, accessors are read here, images decoded with the renderer's PNG
// decoder; the look is compared through the project's renderer, before and
// after, with the pixels near a chart seam told apart.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <numeric>

#include "cli_support.h"
#include "gltf_support.h"  // tinygltf, load() and the validator
#include "intrinsic/render.h"

namespace intrinsic::test {

inline std::vector<double> read_values(const tinygltf::Model& m, int i, int& components) {
  const tinygltf::Accessor& a = m.accessors[static_cast<std::size_t>(i)];
  const tinygltf::BufferView& v = m.bufferViews[static_cast<std::size_t>(a.bufferView)];
  const std::vector<unsigned char>& b = m.buffers[static_cast<std::size_t>(v.buffer)].data;
  components = tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(a.type));
  const int size = tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(a.componentType));
  const std::size_t stride = v.byteStride ? v.byteStride : static_cast<std::size_t>(size * components);
  std::vector<double> out;
  for (std::size_t e = 0; e < a.count; ++e)
    for (int k = 0; k < components; ++k) {
      const unsigned char* p = &b[v.byteOffset + a.byteOffset + e * stride + static_cast<std::size_t>(k * size)];
      if (a.componentType == 5126) { float f; std::memcpy(&f, p, 4); out.push_back(f); }
      else if (a.componentType == 5125) { std::uint32_t x; std::memcpy(&x, p, 4); out.push_back(x); }
      else if (a.componentType == 5123) { std::uint16_t x; std::memcpy(&x, p, 2); out.push_back(x); }
      else out.push_back(*p);
    }
  return out;
}

// Primitive 0 of mesh 0: positions, indices, the TEXCOORD_set in the
// renderer's convention (v up), and the image its base colour reads.
struct Drawn {
  MatrixX3d V;
  MatrixX3i F;
  MatrixX2d UV;  // v up
  Image texture;
};

inline std::string image_bytes(const tinygltf::Model& m, int image, const std::string& folder) {
  const tinygltf::Image& img = m.images[static_cast<std::size_t>(image)];
  if (img.bufferView >= 0) {
    const tinygltf::BufferView& v = m.bufferViews[static_cast<std::size_t>(img.bufferView)];
    const auto& b = m.buffers[static_cast<std::size_t>(v.buffer)].data;
    return std::string(reinterpret_cast<const char*>(&b[v.byteOffset]), v.byteLength);
  }
  return slurp((std::filesystem::path(folder) / img.uri).string());
}

inline Drawn drawn(const std::string& path, int set = 0) {
  const tinygltf::Model m = gltf_test::load(path);
  const tinygltf::Primitive& p = m.meshes.at(0).primitives.at(0);
  Drawn d;
  int c = 0;
  const std::vector<double> pos = read_values(m, p.attributes.at("POSITION"), c);
  d.V = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>(pos.data(), pos.size() / 3, 3);
  const std::vector<double> uv = read_values(m, p.attributes.at("TEXCOORD_" + std::to_string(set)), c);
  d.UV.resize(static_cast<Eigen::Index>(uv.size() / 2), 2);
  for (Eigen::Index i = 0; i < d.UV.rows(); ++i) d.UV.row(i) << uv[2 * i], 1 - uv[2 * i + 1];
  const std::vector<double> idx = read_values(m, p.indices, c);
  d.F.resize(static_cast<Eigen::Index>(idx.size() / 3), 3);
  for (Eigen::Index f = 0; f < d.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) d.F(f, k) = static_cast<int>(idx[static_cast<std::size_t>(3 * f + k)]);
  const int texture = m.materials.at(static_cast<std::size_t>(p.material)).pbrMetallicRoughness.baseColorTexture.index;
  const int image = m.textures.at(static_cast<std::size_t>(texture)).source;
  d.texture = decode_png(image_bytes(m, image, std::filesystem::path(path).parent_path().string()));
  return d;
}

// Per vertex: its connected component through shared vertices (a UV chart:
// glTF splits vertices where UVs differ).
inline std::vector<int> vertex_charts(const Drawn& d, int& count) {
  std::vector<int> parent(static_cast<std::size_t>(d.V.rows()));
  std::iota(parent.begin(), parent.end(), 0);
  std::function<int(int)> find = [&](int x) { return parent[x] == x ? x : parent[x] = find(parent[x]); };
  for (Eigen::Index f = 0; f < d.F.rows(); ++f)
    for (int k = 1; k < 3; ++k) parent[find(d.F(f, k))] = find(d.F(f, 0));
  std::vector<int> id(parent.size(), -1), root_id(parent.size(), -1);
  count = 0;
  for (std::size_t v = 0; v < parent.size(); ++v) {
    const int r = find(static_cast<int>(v));
    if (root_id[r] < 0) root_id[r] = count++;
    id[v] = root_id[r];
  }
  return id;
}

inline RenderOptions view(int size) {
  RenderOptions o;
  o.width = o.height = size;
  o.supersample = 2;
  o.auto_view = false;
  o.azimuth_deg = 35, o.elevation_deg = 25;
  return o;
}

// A render where each chart has its own colour (one texel each, sampled at
// its centre): seams are where neighbouring pixels differ in hue.
inline Image chart_render(const Drawn& d, int size) {
  int count = 0;
  const std::vector<int> chart = vertex_charts(d, count);
  const int w = 128, h = (count + w - 1) / w;
  Image tex(w, h);
  for (int c = 0; c < w * h; ++c) {
    std::uint8_t* p = tex.pixel(c % w, c / w);
    p[0] = 255, p[1] = static_cast<std::uint8_t>(40 + (c * 37) % 200), p[2] = static_cast<std::uint8_t>(40 + (c * 101) % 200);
  }
  MatrixX2d uv(d.V.rows(), 2);
  for (Eigen::Index v = 0; v < d.V.rows(); ++v) {
    const int c = chart[static_cast<std::size_t>(v)];
    uv.row(v) << (c % w + 0.5) / w, 1 - (c / w + 0.5) / h;
  }
  RenderOptions o = view(size);
  o.supersample = 1;
  o.texture = &tex;
  return render_checker(d.V, d.F, uv, o);
}

// True where the 3x3 neighbourhood shows one chart (same colour ratios).
inline std::vector<char> one_chart(const Image& charts) {
  std::vector<char> out(static_cast<std::size_t>(charts.width) * charts.height, 0);
  auto key = [&](int x, int y) {
    const std::uint8_t* p = charts.pixel(x, y);
    return Eigen::Vector2d(p[1] / (p[0] + 1e-9), p[2] / (p[0] + 1e-9));
  };
  for (int y = 1; y + 1 < charts.height; ++y)
    for (int x = 1; x + 1 < charts.width; ++x) {
      const std::uint8_t* c = charts.pixel(x, y);
      if (c[0] == 255 && c[1] == 255 && c[2] == 255) continue;  // background
      bool same = c[0] > 20;
      for (int dy = -1; dy <= 1 && same; ++dy)
        for (int dx = -1; dx <= 1 && same; ++dx) same = (key(x + dx, y + dy) - key(x, y)).cwiseAbs().maxCoeff() < 0.04;
      out[static_cast<std::size_t>(y) * charts.width + x] = same;
    }
  return out;
}

struct LookDifference {
  double mean = 0, mean_away = 0;  // mean absolute difference over the surface's pixels, as a fraction of 255
  long pixels = 0, pixels_away = 0;
};

// Before and after from the same view: the mean absolute difference over
// every pixel of the surface, and over the pixels away from seams of both
// layouts.
inline LookDifference look_difference(const Drawn& before, const Drawn& after, int size) {
  RenderOptions o = view(size);
  o.texture = &before.texture;
  const Image a = render_checker(before.V, before.F, before.UV, o);
  o.texture = &after.texture;
  const Image b = render_checker(after.V, after.F, after.UV, o);
  const std::vector<char> away_a = one_chart(chart_render(before, size)), away_b = one_chart(chart_render(after, size));
  LookDifference d;
  double sum = 0, sum_away = 0;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const std::uint8_t *p = a.pixel(x, y), *q = b.pixel(x, y);
      const bool background = p[0] == 255 && p[1] == 255 && p[2] == 255 && q[0] == 255 && q[1] == 255 && q[2] == 255;
      if (background) continue;
      double diff = 0;
      for (int c = 0; c < 3; ++c) diff += std::abs(p[c] - q[c]) / 3.0;
      sum += diff, ++d.pixels;
      const std::size_t i = static_cast<std::size_t>(y) * size + x;
      if (away_a[i] && away_b[i]) sum_away += diff, ++d.pixels_away;
    }
  d.mean = sum / std::max(1L, d.pixels) / 255;
  d.mean_away = sum_away / std::max(1L, d.pixels_away) / 255;
  return d;
}

}  // namespace intrinsic::test
