// Level-set nested dissection with refined separators (see ordering.h). Work
// is O(nnz) per level of the dissection tree (plus the refinement's, near the
// separators, times a log), so O(nnz log n) in all, with an explicit stack (no
// recursion depth limit) and no allocation per vertex.
//
// The two halves of a separator share no edge, so they are ordered on
// several threads at once: each piece's dissection reads and writes only its
// own vertices' entries of the per-vertex arrays (and reads its neighbours
// in the separators already emitted), and its result depends only on the
// piece, never on which thread takes it or when. So the permutation is the
// same for any thread count.
#include "solve/ordering.h"

#include "solve/ordering_refine.h"
#include "util/parallel_for.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <system_error>
#include <thread>

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
// The refined separator keeps each half within 40/60 of the two, as the
// level cut does; a few passes (each stops on its own once it stalls).
constexpr double kMaxFraction = 0.6;
constexpr int kPasses = 4;
// Pieces at least this large get their separator refined and try a second
// start vertex. Below it a piece's separator costs little (its dense block
// is tens of rows), and at 300k vertices refining them all would cost 1.6x
// the ordering time for 2-3% fewer flops.
constexpr int kRefineAbove = 1000;
// Halves at least this large go to the shared queue for any idle thread;
// smaller ones stay with the thread that cut them (no locking per piece).
constexpr int kShareAbove = 5000;
// Pieces at most this large (and at most a quarter of the graph) are copied
// into a compact graph of their own (Dissection::dissect_compact), where
// the piece and all its descendants are searched and refined in cache
// (docs/performance.md#fill-reducing-ordering: a few percent of the
// ordering's CPU).
constexpr int kCompactBelow = 1 << 16;

// What the threads share: the graph, the per-vertex arrays (each piece
// touches only its own vertices' entries), the permutation (each piece
// writes its own positions) and the queue of pieces waiting for a thread.
struct Node {
  int owner;
  int level[2];  // the current search's (Dissection::cur_) and a second one's (retry_from)
};

struct Shared {
  Shared(const SparseMatrix& A, int compact)
      : n(static_cast<int>(A.rows())),
        compact_below(compact),
        begin(A.outerIndexPtr()),
        end(A.innerNonZeroPtr()),
        index(A.innerIndexPtr()),
        owner(n, 0),
        node(n, Node{0, {-1, -1}}),
        side(n, 0),
        local(n, 0),
        perm(n, 0) {}
  int n;
  int compact_below;  // see kCompactBelow
  const int* begin;
  const int* end;  // non-null for uncompressed matrices
  const int* index;
  std::vector<int> owner;  // the refiner's copy of node[].owner
  // Each vertex's owner and its levels in two searches side by side: a
  // search's test of a neighbour (owner, then level) touches one cache
  // line instead of two. Both levels are -1 between uses.
  std::vector<Node> node;
  std::vector<signed char> side;  // half (0, 1) or separator (2) of a piece being split
  std::vector<int> local;         // a compacted piece's vertex's id in its copy
  std::vector<int> perm;
  // Owner tags: only equality with a piece's own tag matters, and no two
  // pieces alive at once are adjacent, so the values may depend on timing.
  std::atomic<int> next_tag{1};
  std::mutex mutex;
  std::condition_variable wake;
  std::vector<Piece> queue;
  int busy = 0;  // threads working on a piece taken from the queue
  std::exception_ptr failure;  // the first exception a thread caught
};

// One thread's dissection: its own stack of pieces and search buffers.
class Dissection {
 public:
  explicit Dissection(Shared& shared)
      : shared_(shared),
        n_(shared.n),
        perm_(shared.perm),
        whole_refiner_(shared.begin, shared.end, shared.index, shared.n),
        compact_refiner_(nullptr, nullptr, nullptr, 0) {
    view_whole();
  }

  // Breadth-first search from `source` over the vertices tagged `tag`;
  // visited vertices go to `order` with their level in node_[].level[cur_],
  // and count[l] = |level l|. Returns the number of levels. The levels are
  // contiguous in `order` (level l starts at count[0] + ... + count[l-1]),
  // which spares the callers a pass over the piece to count or find them.
  //
  // `size` is the number of vertices tagged `tag`: `order` gets room for all
  // of them up front, every neighbour is written at its end and kept only if
  // new, and the level goes to it or to a dummy, so that the inner loop
  // has no capacity check and little to branch on (measured: 11% less
  // ordering CPU at 1M vertices with the pass fusions below; a fully
  // branch-free form with conditional moves was slower).
  int bfs(int source, int tag, int size, std::vector<int>& order, std::vector<long>& count) {
    if (static_cast<int>(order.size()) < size + 1) order.resize(size + 1);
    int* out = order.data();
    int tail = 0, dummy = 0;
    out[tail++] = source;
    count.assign(1, 1);
    node_[source].level[cur_] = 0;
    for (int q = 0; q < tail; ++q) {
      const int v = out[q];
      const int next = node_[v].level[cur_] + 1;
      const int found = tail;
      for (int k = begin_[v], e = end_of(v); k < e; ++k) {
        const int w = index_[k];
        Node& nw = node_[w];
        const bool fresh = (nw.owner == tag) & (nw.level[cur_] < 0);
        *(fresh ? &nw.level[cur_] : &dummy) = next;
        out[tail] = w;
        tail += fresh;
      }
      if (tail > found) {
        if (next == static_cast<int>(count.size())) count.push_back(0);
        count[next] += tail - found;
      }
    }
    order.resize(tail);
    return static_cast<int>(count.size());
  }
  // Among the levels that split the piece no worse than 40/60, the smallest
  // one; the most balanced level if none does (count[l] = |level l|).
  static int choose_cut(int levels, int size, const std::vector<long>& count) {
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
    for (int v : order) node_[v].level[cur_] = -1;
  }

  // Takes pieces from the shared queue until every piece is done, or until
  // some thread failed (out of memory): then all stop and the caller
  // rethrows that thread's exception.
  void work(int leaf_size) {
    for (;;) {
      {
        std::unique_lock<std::mutex> lock(shared_.mutex);
        shared_.wake.wait(lock, [&] { return !shared_.queue.empty() || shared_.busy == 0 || shared_.failure; });
        if (shared_.queue.empty() || shared_.failure) return;  // all done, or given up
        stack_.push_back(std::move(shared_.queue.back()));
        shared_.queue.pop_back();
        ++shared_.busy;
      }
      std::exception_ptr failure;
      try {
        while (!stack_.empty()) {
          Piece piece = std::move(stack_.back());
          stack_.pop_back();
          dissect(piece, leaf_size);
        }
      } catch (...) {
        failure = std::current_exception();
      }
      std::lock_guard<std::mutex> lock(shared_.mutex);
      if (failure && !shared_.failure) shared_.failure = failure;
      if ((--shared_.busy == 0 && shared_.queue.empty()) || shared_.failure) shared_.wake.notify_all();
    }
  }

 private:
  // Places vs at perm[first...] (by their ids in the whole graph). They keep
  // the tag of the piece they came from: no piece gets that tag again, so
  // no later search or move takes them (marking them done would be one more
  // pass over every vertex, missing the cache).
  void emit(const std::vector<int>& vs, int first) {
    for (size_t i = 0; i < vs.size(); ++i) perm_[first + static_cast<int>(i)] = global_ ? global_[vs[i]] : vs[i];
  }

  // Pushes two tagged halves so that a is taken next; a large b of the
  // whole graph goes to the shared queue for another thread (a compact copy
  // is this thread's alone).
  void push_halves(Piece&& a, Piece&& b) {
    if (!global_ && static_cast<int>(b.vertices.size()) >= kShareAbove) {
      std::lock_guard<std::mutex> lock(shared_.mutex);
      shared_.queue.push_back(std::move(b));
      shared_.wake.notify_one();
    } else {
      stack_.push_back(std::move(b));
    }
    stack_.push_back(std::move(a));
  }
  int new_tag() { return shared_.next_tag.fetch_add(1, std::memory_order_relaxed); }

  // Emits a piece or splits it in two plus a separator (emitted last).
  void dissect(Piece& piece, int leaf_size) {
    const int size = static_cast<int>(piece.vertices.size());
    if (size <= leaf_size) {
      emit(piece.vertices, piece.first);
      return;
    }
    if (!global_ && size <= shared_.compact_below) {
      dissect_compact(piece, leaf_size);
      return;
    }
    // A half starts from a corner, next to an end of its parent's separator
    // (split_at_cut); starting from the parent's start, as this did before,
    // gives levels parallel to the separator just cut, long and thin (at
    // 100k vertices: 1.4-1.5 sqrt(s) instead of 0.8-1.0). Otherwise search
    // once to find a far vertex.
    if (piece.start < 0) {
      bfs(piece.vertices[0], piece.tag, size, order_, count_);
      piece.start = order_.back();
      clear_levels(order_);
    }
    const int levels = bfs(piece.start, piece.tag, size, order_, count_);
    if (static_cast<int>(order_.size()) < size) {
      split_disconnected(piece);
      return;
    }
    if (levels < 3) {  // no interior level to cut at
      clear_levels(order_);
      emit(order_, piece.first);
      return;
    }
    int cut = choose_cut(levels, size, count_);
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
      cut = retry_from(piece, cut, size, middle_of_level(cut), 0.9, true);
    // The start is a guess (a corner of the piece); the vertex farthest
    // from it is a second one, kept if its separator is smaller.
    if (size >= kRefineAbove) cut = retry_from(piece, cut, size, order_.back(), 1.0, false);
    split_at_cut(piece, cut);
  }

  // Disconnected piece (order_ holds the search from its start): the
  // component found first and the rest, no separator.
  void split_disconnected(const Piece& piece) {
    Piece a{order_, piece.first, new_tag(), order_.back()},
        b{{}, piece.first + static_cast<int>(order_.size()), new_tag()};
    // One pass tags both halves and clears the search's levels.
    for (int v : piece.vertices) {
      Node& node = node_[v];
      if (node.level[cur_] < 0) {
        b.vertices.push_back(v);
        owner_[v] = node.owner = b.tag;
      } else {
        node.level[cur_] = -1;
        owner_[v] = node.owner = a.tag;
      }
    }
    push_halves(std::move(a), std::move(b));
  }

  // The middle vertex of level `cut` of the current search, in search order.
  int middle_of_level(int cut) const {
    long first = 0;
    for (int l = 0; l < cut; ++l) first += count_[l];
    return order_[first + count_[cut] / 2];
  }

  // Searches again from `source`; keeps that search (in order_, count_,
  // piece.start) if its separator is smaller than `keep_below` times the
  // current one, else restores the current one. Returns the cut level to use.
  // The levels of the search not kept are left for split_at_cut to clear
  // unless `clear` (both searches cover the whole piece, so its pass over
  // order_ clears them on the same cache lines).
  int retry_from(Piece& piece, int cut, int size, int source, double keep_below, bool clear) {
    const long first_separator = count_[cut];
    std::vector<int>& other = other_order_;
    cur_ ^= 1;  // the second search writes the spare level
    std::vector<long>& other_count = other_count_;
    const int other_levels = bfs(source, piece.tag, size, other, other_count);
    cur_ ^= 1;
    const int other_cut = other_levels >= 3 ? choose_cut(other_levels, size, other_count) : -1;
    const bool keep = other_cut >= 0 && other_count[other_cut] < keep_below * static_cast<double>(first_separator);
    if (keep) {
      piece.start = source;
      order_.swap(other);
      count_.swap(other_count);
      cur_ ^= 1;
    }
    if (clear)
      for (int v : other) node_[v].level[cur_ ^ 1] = -1;  // the search not kept
    return keep ? other_cut : cut;
  }

  // One end of the separator `sep` (side_ 2): the last vertex of a search
  // along the separator from its first vertex. The halves' searches start
  // next to it, at a corner of each half, so that their levels cross the
  // half rather than run along the separator just cut.
  int separator_end(const std::vector<int>& sep, int tag) {
    std::vector<int>& queue = other_order_;
    queue.clear();
    queue.push_back(sep[0]);
    node_[sep[0]].level[cur_] = 0;
    for (size_t q = 0; q < queue.size(); ++q) {
      const int v = queue[q];
      for (int k = begin_[v], e = end_of(v); k < e; ++k) {
        const int w = index_[k];
        if (node_[w].owner != tag || side_[w] != 2 || node_[w].level[cur_] >= 0) continue;
        node_[w].level[cur_] = 0;
        queue.push_back(w);
      }
    }
    clear_levels(queue);
    return queue.back();
  }
  // A neighbour of v on side `half` of the piece tagged `tag`, or -1.
  int neighbour_on(int v, int half, int tag) const {
    for (int k = begin_[v], e = end_of(v); k < e; ++k)
      if (owner_[index_[k]] == tag && side_[index_[k]] == half) return index_[k];
    return -1;
  }
  int end_of(int v) const { return end_ ? begin_[v] + end_[v] : begin_[v + 1]; }

  // Splits the searched piece into the levels before and after `cut`, moves
  // that separator to a shorter one nearby (ordering_refine.h), and emits it
  // after both halves. Each pass over the piece does all it can (the levels
  // are cleared as they are read, the halves tagged as they are gathered):
  // at the top levels each pass misses the cache on every vertex.
  void split_at_cut(const Piece& piece, int cut) {
    std::vector<int> separator;
    long below = 0;
    for (int v : order_) {
      Node& node = node_[v];
      const int l = node.level[cur_];
      node.level[0] = node.level[1] = -1;  // this search's and any other's (retry_from)
      side_[v] = static_cast<signed char>(l < cut ? 0 : l > cut ? 1 : 2);
      if (l == cut) separator.push_back(v);
      below += l < cut;
    }
    const long above = static_cast<long>(order_.size()) - below - static_cast<long>(separator.size());
    if (static_cast<long>(order_.size()) >= kRefineAbove)
      refiner_->refine(separator, side_, owner_, piece.tag, below, above, kMaxFraction, kPasses);
    // The halves' starts, found while their vertices still carry the piece's tag.
    Piece a{{}, piece.first, new_tag()}, b{{}, 0, new_tag()};
    const int end = separator.empty() ? -1 : separator_end(separator, piece.tag);
    if (end >= 0) {
      a.start = neighbour_on(end, 0, piece.tag);
      b.start = neighbour_on(end, 1, piece.tag);
    }
    a.vertices.reserve(static_cast<size_t>(below));
    b.vertices.reserve(static_cast<size_t>(above));
    for (int v : order_) {
      const int s = side_[v];
      if (s == 2) continue;
      Piece& half = s == 0 ? a : b;
      half.vertices.push_back(v);
      owner_[v] = node_[v].owner = half.tag;
    }
    b.first = piece.first + static_cast<int>(a.vertices.size());
    emit(separator, b.first + static_cast<int>(b.vertices.size()));
    push_halves(std::move(a), std::move(b));
  }

  // Copies the piece's subgraph into compact_ and dissects the piece and all
  // its descendants there. A piece's vertices lie all over the whole
  // graph's arrays, between other pieces'; the copy (ids in the piece's
  // order, which is a search's, so neighbours lie close) fits in cache. The
  // gain is small (1-10% of the ordering's CPU on a 1M-vertex disk, none
  // measurable on a 0.5M scan): below 64k vertices the searches cost more
  // in work per edge than in misses. The copy keeps each vertex's neighbours in the piece
  // in A's order and the vertices in the piece's, and the refiner breaks
  // ties by the whole graph's ids, so every search and move visits the same
  // vertices in the same order as on the whole graph and the permutation is
  // the same. The diagonal is left out: no search or move uses it.
  void dissect_compact(const Piece& piece, int leaf_size) {
    const int size = static_cast<int>(piece.vertices.size());
    Compact& c = compact_;
    int* local = shared_.local.data();
    c.global.assign(piece.vertices.begin(), piece.vertices.end());
    for (int i = 0; i < size; ++i) local[c.global[i]] = i;
    c.begin.resize(size + 1);
    c.begin[0] = 0;
    c.index.clear();
    for (int i = 0; i < size; ++i) {
      const int v = c.global[i];
      for (int k = begin_[v], e = end_of(v); k < e; ++k) {
        const int w = index_[k];
        if (w != v && node_[w].owner == piece.tag) c.index.push_back(local[w]);
      }
      c.begin[i + 1] = static_cast<int>(c.index.size());
    }
    c.owner.assign(size, piece.tag);
    c.node.assign(size, Node{piece.tag, {-1, -1}});
    c.side.assign(size, 0);
    Piece root{std::vector<int>(size), piece.first, piece.tag, piece.start < 0 ? -1 : local[piece.start]};
    for (int i = 0; i < size; ++i) root.vertices[i] = i;
    view_compact();
    // Its descendants go on top of this thread's stack and are all done
    // before the pieces of the whole graph under them.
    const size_t below = stack_.size();
    stack_.push_back(std::move(root));
    try {
      while (stack_.size() > below) {
        Piece p = std::move(stack_.back());
        stack_.pop_back();
        dissect(p, leaf_size);
      }
    } catch (...) {
      stack_.resize(below);
      view_whole();
      throw;
    }
    view_whole();
  }

  // Points the dissection at the whole graph's shared arrays, or at compact_.
  void view_whole() {
    begin_ = shared_.begin;
    end_ = shared_.end;
    index_ = shared_.index;
    owner_ = shared_.owner.data();
    node_ = shared_.node.data();
    side_ = shared_.side.data();
    global_ = nullptr;
    refiner_ = &whole_refiner_;
  }
  void view_compact() {
    Compact& c = compact_;
    begin_ = c.begin.data();
    end_ = nullptr;
    index_ = c.index.data();
    owner_ = c.owner.data();
    node_ = c.node.data();
    side_ = c.side.data();
    global_ = c.global.data();
    compact_refiner_.bind(begin_, end_, index_, global_, static_cast<int>(c.global.size()));
    refiner_ = &compact_refiner_;
  }

  Shared& shared_;
  int n_;  // the whole graph's
  // The graph being dissected: the whole one (the shared arrays) or a
  // piece's compact copy (compact_, global_ its vertices' ids in the whole
  // graph; null for the whole graph). owner_ is the refiner's copy of
  // node_[].owner; node_ holds the levels, where cur_ says which of the two
  // is this thread's current search (retry_from keeps a second search by
  // flipping it).
  const int* begin_;
  const int* end_;
  const int* index_;
  int* owner_;
  Node* node_;
  signed char* side_;
  const int* global_;
  SeparatorRefiner* refiner_;
  int cur_ = 0;
  std::vector<int>& perm_;
  SeparatorRefiner whole_refiner_, compact_refiner_;
  struct Compact {
    std::vector<int> begin, index, global, owner;
    std::vector<Node> node;
    std::vector<signed char> side;
  } compact_;
  // This thread's pieces still to dissect and search buffers reused across pieces.
  std::vector<Piece> stack_;
  std::vector<int> order_, other_order_;
  std::vector<long> count_, other_count_;
};

}  // namespace

std::vector<int> level_set_nested_dissection(const SparseMatrix& A, int leaf_size, int compact_below) {
  if (A.rows() == 0) return {};
  leaf_size = std::max(leaf_size, 3);
  // A piece as large as the graph gains nothing from a copy: its vertices
  // are not scattered.
  if (compact_below < 0) compact_below = std::min(kCompactBelow, static_cast<int>(A.rows()) / 4);
  Shared shared(A, compact_below);
  shared.queue.push_back({std::vector<int>(shared.n), 0, 0});
  for (int v = 0; v < shared.n; ++v) shared.queue.back().vertices[v] = v;
  // Below ~20k vertices per thread a thread costs more than it saves.
  const int threads = parallel_parts(shared.n, 20000);
  std::vector<std::thread> helpers;
  try {
    for (int t = 1; t < threads; ++t)
      helpers.emplace_back([&shared, leaf_size] {
        try {
          Dissection(shared).work(leaf_size);
        } catch (...) {  // its own buffers could not be allocated
          std::lock_guard<std::mutex> lock(shared.mutex);
          if (!shared.failure) shared.failure = std::current_exception();
          shared.wake.notify_all();
        }
      });
  } catch (const std::system_error&) {
    // No more threads to be had: the ones started (or this one alone) do all.
  }
  try {
    Dissection(shared).work(leaf_size);
  } catch (...) {
    std::lock_guard<std::mutex> lock(shared.mutex);
    if (!shared.failure) shared.failure = std::current_exception();
    shared.wake.notify_all();
  }
  for (std::thread& t : helpers) t.join();
  if (shared.failure) std::rethrow_exception(shared.failure);
  return std::move(shared.perm);
}

}  // namespace intrinsic::detail
