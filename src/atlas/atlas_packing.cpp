// Packing: every chart already has UV area = 3D area (one texel density for
// all). The steps, one file each under packing/:
//   1. chart_pose:   turn each chart to its smallest bounding box (and a few
//                    more angles for charts that fill it poorly);
//   2. texel_mask:   rasterize each pose at a scale into the texels it covers,
//                    dilated by the padding;
//   3. bitmap:       the layout's taken texels and the first-fit scan;
//   4. placement:    place the masks, largest first, where the layout's
//                    square grows least;
//   5. scale_search: the largest scale at which every chart fits.
// Here the layout is then fitted into [0,1]^2 by one similarity. Boxes alone
// (a skyline of rectangles) left a third of the square empty on the assets;
// masks let small charts sit in the concave parts of large ones.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

#include "atlas/atlas_internal.h"
#include "atlas/packing/chart_pose.h"
#include "atlas/packing/scale_search.h"
#include "atlas/thresholds.h"
#include "intrinsic/error.h"

namespace intrinsic::detail {
namespace {

// The smallest box of the points UV and the fraction `area` fills of it.
ChartBox box_of(const MatrixX2d& UV, double area) {
  double box = 0;
  const MatrixX2d turned = packing::turned_to(UV, packing::smallest_box_angle(UV, box));
  const Eigen::Vector2d size = turned.colwise().maxCoeff().transpose();
  ChartBox b;
  b.longer = size.maxCoeff(), b.shorter = size.minCoeff();
  b.fill = b.longer * b.shorter > 0 ? area / (b.longer * b.shorter) : 1;
  return b;
}

}  // namespace

ChartBox chart_box(const FlatChart& chart) { return box_of(chart.UV, chart.summary.area_3d); }

ChartBox planar_chart_box(const ChartMesh& chart) {
  const MatrixX3d& V = chart.data.V;
  const MatrixX3i& F = chart.data.F;
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  double area = 0;
  for (int f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d n = (V.row(F(f, 1)) - V.row(F(f, 0))).cross(V.row(F(f, 2)) - V.row(F(f, 0)));
    normal += n, area += n.norm() / 2;
  }
  if (!(normal.norm() > 0)) return {};
  normal.normalize();
  const Eigen::Vector3d u = normal.unitOrthogonal(), v = normal.cross(u);
  MatrixX2d P(V.rows(), 2);
  P.col(0) = V * u;
  P.col(1) = V * v;
  return box_of(P, area);
}

bool packs_well(const ChartBox& box, double surface_area, double part_diameter) {
  const double box_area = box.longer * box.shorter;
  // Too long, whatever its area: the square holding the layout is at least
  // as long (a hairline beam of no area set the side of regr01's square).
  const bool strip = box.longer >= kStripAspect * box.shorter && box.longer <= kStripPartDiameters * part_diameter &&
                     box.fill * box_area >= kStripMinShare * surface_area;
  if (!strip && box.longer * box.longer > kMaxSideOverSurface * kMaxSideOverSurface * surface_area) return false;
  // A box this small wastes little whatever the chart's shape (and the
  // packer puts small masks into the gaps of large ones).
  if (box_area < kSparseMinShare * surface_area) return true;
  return box.fill >= kMinBoxFill;
}

namespace {

// The charts turned to their poses (steps 1 and 2's input); `area` their total.
// `keep`: each chart only in the orientation it came with.
std::vector<packing::PackChart> posed(std::vector<FlatChart>& charts, double& area, bool keep) {
  area = 0;
  for (FlatChart& chart : charts) {
    if (!keep) packing::orient_chart(chart);
    area += chart.summary.area_3d;
  }
  std::vector<packing::PackChart> pack(charts.size());
  if (keep) {
    for (size_t c = 0; c < charts.size(); ++c) {
      pack[c].F = &charts[c].mesh.data.F;
      pack[c].poses.push_back(packing::turned_to(charts[c].UV, 0.0));
    }
    return pack;
  }
  const std::vector<std::vector<double>> angles = packing::all_pose_angles(charts, area, packing::PoseOptions{});
  for (size_t c = 0; c < charts.size(); ++c) {
    pack[c].F = &charts[c].mesh.data.F;
    for (double angle : angles[c]) pack[c].poses.push_back(packing::turned_to(charts[c].UV, angle));
  }
  return pack;
}

// Chart c's four quarter-turn masks at `scale` cells per unit, the scale
// lowered until one fits an empty page of `side` cells (a chart larger than
// a page at the asked density is shrunk, never dropped).
std::vector<packing::Mask> fitting_masks(const packing::PackChart& c, double& scale, int side, int pad, bool& shrunk) {
  shrunk = false;
  for (int tries = 0;; ++tries) {
    std::vector<packing::Mask> m = packing::quarter_turn_masks(*c.F, c.poses[0], scale, pad);
    int smallest = INT32_MAX;
    for (const packing::Mask& k : m) smallest = std::min(smallest, std::max(k.w, k.h));
    if (smallest <= side || tries > 60) return m;
    shrunk = true;
    scale *= std::max(0.5, 0.98 * (side - 2 * pad - 2) / std::max(1.0, smallest - 2.0 * pad));
  }
}

// Lightmap pages (texels_per_unit > 0): every chart at one density, pages
// of `resolution` texels filled in turn, page k at u in [k, k + 1] (UDIM).
double pack_on_pages(std::vector<FlatChart>& charts, const PackOptions& o, PageLayout& out) {
  double area = 0;
  const std::vector<packing::PackChart> pack = posed(charts, area, o.keep_orientation);
  // Pages over kMaxPackBitmap texels are packed on cells of `zoom` texels.
  const int zoom = (o.resolution + kMaxPackBitmap - 1) / kMaxPackBitmap;
  const int side = o.resolution / zoom;
  const int pad = static_cast<int>(std::ceil(o.padding / zoom - 1e-9));
  const int edge = pad - (pad + 1) / 2;  // half the padding at the page's border, as pack_flat_charts
  std::vector<double> scale(charts.size(), o.texels_per_unit / zoom);
  std::vector<std::vector<packing::Mask>> masks(charts.size());
  for (size_t c = 0; c < charts.size(); ++c) {
    bool shrunk = false;
    masks[c] = fitting_masks(pack[c], scale[c], side + 2 * edge, pad, shrunk);
    if (shrunk) out.shrunk.push_back(static_cast<int>(c));
  }
  std::vector<packing::Placement> at;
  const int pages = packing::place_on_pages(masks, side + 2 * edge, 4, at, out.chart_page, o.max_pages);
  if (pages < 0)
    throw_input("the charts need more than " + std::to_string(o.max_pages) + " pages of " +
                std::to_string(o.resolution) + " texels at " + std::to_string(o.texels_per_unit) +
                " texels per unit (max_pages)");
  out.page_utilization.assign(static_cast<size_t>(pages), 0.0);
  const double texels = static_cast<double>(o.resolution) * o.resolution;
  for (size_t c = 0; c < charts.size(); ++c) {
    const packing::Placement& p = at[c];
    charts[c].UV = packing::texel_coordinates(pack[c].poses[0], scale[c], p.pose % 4);
    charts[c].summary.rotated = p.pose != 0;
    charts[c].UV.col(0).array() += p.x + pad - edge;
    charts[c].UV.col(1).array() += p.y + pad - edge;
    charts[c].UV *= static_cast<double>(zoom) / o.resolution;
    charts[c].UV = charts[c].UV.cwiseMax(0.0).cwiseMin(1.0);  // rounding only
    charts[c].UV.col(0).array() += out.chart_page[c];
    const double s = scale[c] * zoom;
    out.page_utilization[static_cast<size_t>(out.chart_page[c])] += charts[c].summary.area_3d * s * s / texels;
  }
  double sum = 0;
  for (double u : out.page_utilization) sum += u;
  return sum / pages;
}

}  // namespace

double pack_flat_charts(std::vector<FlatChart>& charts, const PackOptions& options, PageLayout* pages) {
  if (charts.empty()) return 0;
  if (options.texels_per_unit > 0) {
    PageLayout unused;
    return pack_on_pages(charts, options, pages ? *pages : unused);
  }
  double area = 0;
  const std::vector<packing::PackChart> pack = posed(charts, area, options.keep_orientation);
  // Larger textures pack on a coarser grid (thresholds.h).
  const int side = std::min(options.resolution, kMaxPackBitmap);
  const int pad = static_cast<int>(std::ceil(options.padding * side / options.resolution - 1e-9));
  // Half the padding (rounded up) around the border, as a neighbour's half
  // would complete it: the bitmap reaches `edge` texels past the square on
  // every side, where nothing is ever taken but dilated masks may lie.
  const int edge = pad - (pad + 1) / 2;
  int bitmap = side + 2 * edge;
  const packing::Layout l = packing::search_layout(pack, std::max(area, 1e-300), bitmap, pad);
  const double square = l.extent - 2 * edge;  // texels; the layout is [edge, extent - edge] of the bitmap
  for (size_t c = 0; c < charts.size(); ++c) {
    const packing::Placement& p = l.at[c];
    const int angle = p.pose / 4, turns = p.pose % 4;
    charts[c].UV = packing::texel_coordinates(pack[c].poses[angle], l.scale / l.zoom, turns);
    charts[c].summary.rotated = p.pose != 0;
    charts[c].UV.col(0).array() += p.x + l.pad;
    charts[c].UV.col(1).array() += p.y + l.pad;
    charts[c].UV = charts[c].UV * l.zoom;
    charts[c].UV.array() -= edge;
    charts[c].UV /= square;
    charts[c].UV = charts[c].UV.cwiseMax(0.0).cwiseMin(1.0);  // rounding only
  }
  const double used = l.scale / square;
  return area * used * used;
}

}  // namespace intrinsic::detail
