// Level-set nested dissection (see ordering.h). Work is O(nnz) per level of
// the dissection tree, so O(nnz log n) in all, with an explicit stack (no
// recursion depth limit) and no allocation per vertex.
#include "solve/ordering.h"

#include <algorithm>
#include <cmath>

namespace intrinsic::detail {
namespace {

struct Piece {
  std::vector<int> vertices;
  int first;      // first position of the piece in the permutation
  int tag;        // owner[] value of its vertices
  int start = -1; // a vertex known to be far from the others, or -1
};

// Pieces at least this large try a second start vertex (see run()).
constexpr int kRetryAbove = 2000;

class Dissection {
 public:
  explicit Dissection(const SparseMatrix& A)
      : n_(static_cast<int>(A.rows())),
        begin_(A.outerIndexPtr()),
        end_(A.innerNonZeroPtr()),
        index_(A.innerIndexPtr()),
        owner_(n_, 0),
        level_(n_, -1) {}

  // Breadth-first search from `source` over the vertices tagged `tag`;
  // visited vertices go to `order` with their level in level_. Returns the
  // number of levels.
  int bfs(int source, int tag, std::vector<int>& order) {
    order.clear();
    order.push_back(source);
    level_[source] = 0;
    for (size_t q = 0; q < order.size(); ++q) {
      const int v = order[q];
      const int e = end_ ? begin_[v] + end_[v] : begin_[v + 1];
      for (int k = begin_[v]; k < e; ++k) {
        const int w = index_[k];
        if (owner_[w] != tag || level_[w] >= 0) continue;
        level_[w] = level_[v] + 1;
        order.push_back(w);
      }
    }
    return level_[order.back()] + 1;
  }
  // Among the levels that split the piece no worse than 40/60, the smallest
  // one; the most balanced level if none does. Fills count[l] = |level l|.
  int choose_cut(const std::vector<int>& order, int levels, int size, std::vector<long>& count) const {
    count.assign(levels, 0);
    for (int v : order) ++count[level_[v]];
    int cut = -1, balanced = 1;
    long below = count[0], best_gap = -1;
    for (int l = 1; l + 1 < levels; ++l) {
      const long above = size - below - count[l];
      const long gap = std::labs(above - below);
      if (best_gap < 0 || gap < best_gap) { best_gap = gap; balanced = l; }
      if (5 * std::min(below, above) >= 2 * (below + above) && (cut < 0 || count[l] < count[cut])) cut = l;
      below += count[l];
    }
    return cut < 0 ? balanced : cut;
  }
  void clear_levels(const std::vector<int>& order) {
    for (int v : order) level_[v] = -1;
  }

  // The fill-reducing permutation: perm[i] is the vertex eliminated i-th.
  std::vector<int> run(int leaf_size) {
    perm_.assign(n_, 0);
    stack_.clear();
    stack_.push_back({std::vector<int>(n_), 0, 0});
    for (int v = 0; v < n_; ++v) stack_.back().vertices[v] = v;
    next_tag_ = 1;
    while (!stack_.empty()) {
      Piece piece = std::move(stack_.back());
      stack_.pop_back();
      dissect(piece, leaf_size);
    }
    return std::move(perm_);
  }

 private:
  // Places vs at perm[first...] and marks them as done (owner -1).
  void emit(const std::vector<int>& vs, int first) {
    for (size_t i = 0; i < vs.size(); ++i) {
      perm_[first + static_cast<int>(i)] = vs[i];
      owner_[vs[i]] = -1;
    }
  }

  // Tags the two halves' vertices and pushes them so that a is taken next.
  void push_halves(Piece&& a, Piece&& b) {
    for (int v : a.vertices) owner_[v] = a.tag;
    for (int v : b.vertices) owner_[v] = b.tag;
    stack_.push_back(std::move(b));
    stack_.push_back(std::move(a));
  }

  // Emits a piece or splits it in two plus a separator (emitted last).
  void dissect(Piece& piece, int leaf_size) {
    const int size = static_cast<int>(piece.vertices.size());
    if (size <= leaf_size) {
      emit(piece.vertices, piece.first);
      return;
    }
    // A half's peripheral vertex is known from its parent's search: the
    // parent's start for the near half, its last vertex for the far one.
    // Otherwise search once to find one.
    if (piece.start < 0) {
      bfs(piece.vertices[0], piece.tag, order_);
      piece.start = order_.back();
      clear_levels(order_);
    }
    const int levels = bfs(piece.start, piece.tag, order_);
    if (static_cast<int>(order_.size()) < size) {
      split_disconnected(piece);
      return;
    }
    if (levels < 3) {  // no interior level to cut at
      clear_levels(order_);
      emit(order_, piece.first);
      return;
    }
    int cut = choose_cut(order_, levels, size, count_);
    // Large pieces whose separator is long for their size (a planar piece
    // of s vertices has one of 1.1-1.4 sqrt(s) here): also cut from a
    // vertex of the chosen level and keep the thinner separator. A
    // peripheral start is right on a disk, but on the natural map's system
    // (two copies of the mesh joined along the boundary: a sphere) it is a
    // pole, and its half-way levels run around the boundary (2.2 sqrt(s));
    // from a boundary vertex they are great circles through both copies
    // (1M vertices: 222 -> 168 Gflop; METIS 92, but its ordering alone
    // takes 16 s there).
    if (size >= std::max(kRetryAbove, n_ / 32) && count_[cut] > 1.8 * std::sqrt(static_cast<double>(size)))
      cut = retry_from_separator(piece, cut, size);
    split_at_cut(piece, cut);
  }

  // Disconnected piece (order_ holds the search from its start): the
  // component found first and the rest, no separator.
  void split_disconnected(const Piece& piece) {
    Piece a{order_, piece.first, next_tag_++, order_.back()},
        b{{}, piece.first + static_cast<int>(order_.size()), next_tag_++};
    for (int v : piece.vertices)
      if (level_[v] < 0) b.vertices.push_back(v);
    clear_levels(order_);
    push_halves(std::move(a), std::move(b));
  }

  // Searches again from the middle vertex of level `cut`; keeps that search
  // (in order_, count_, piece.start) if its separator is at least 10%
  // smaller, else restores the first one. Returns the cut level to use.
  int retry_from_separator(Piece& piece, int cut, int size) {
    const long first_separator = count_[cut];
    int mid = -1;  // the middle vertex of the level, in search order
    long seen = 0;
    for (int v : order_)
      if (level_[v] == cut && seen++ <= first_separator / 2) mid = v;
    std::vector<int> other;
    clear_levels(order_);
    const int other_levels = bfs(mid, piece.tag, other);
    std::vector<long> other_count;
    const int other_cut = other_levels >= 3 ? choose_cut(other, other_levels, size, other_count) : -1;
    if (other_cut >= 0 && 10 * other_count[other_cut] < 9 * first_separator) {
      piece.start = mid;
      order_.swap(other);
      count_.swap(other_count);
      return other_cut;
    }
    clear_levels(other);
    bfs(piece.start, piece.tag, order_);
    return cut;
  }

  // Splits the searched piece into the levels before and after `cut`, and
  // emits level `cut` (the separator) after both.
  void split_at_cut(const Piece& piece, int cut) {
    Piece a{{}, piece.first, next_tag_++, piece.start}, b{{}, 0, next_tag_++, order_.back()};
    std::vector<int> separator;
    for (int v : order_) {
      if (level_[v] < cut) a.vertices.push_back(v);
      else if (level_[v] > cut) b.vertices.push_back(v);
      else separator.push_back(v);
    }
    clear_levels(order_);
    b.first = piece.first + static_cast<int>(a.vertices.size());
    emit(separator, b.first + static_cast<int>(b.vertices.size()));
    push_halves(std::move(a), std::move(b));
  }

  int n_;
  const int* begin_;
  const int* end_;  // non-null for uncompressed matrices
  const int* index_;
  std::vector<int> owner_, level_;
  // State of run(): the permutation, the pieces still to dissect, the next
  // unused owner tag, and search buffers reused across pieces.
  std::vector<int> perm_;
  std::vector<Piece> stack_;
  int next_tag_ = 1;
  std::vector<int> order_;
  std::vector<long> count_;
};

}  // namespace

std::vector<int> level_set_nested_dissection(const SparseMatrix& A, int leaf_size) {
  if (A.rows() == 0) return {};
  return Dissection(A).run(std::max(leaf_size, 3));
}

}  // namespace intrinsic::detail
