// Fiduccia-Mattheyses refinement of a vertex separator (see ordering_refine.h;
// the vertex form of Fiduccia & Mattheyses 1982 as in METIS's node
// refinement, written from that description).
//
// Moving separator vertex v into half t takes it off the separator and pulls
// its neighbours in the other half into it, so its gain is 1 minus the number
// of those neighbours. Each pass moves the best vertex repeatedly (either
// direction, gains kept up to date in two heaps), even through moves that
// grow the separator, for a while, then rolls back to the best state seen:
// that lets a pass walk the separator across a bump it could not shave one
// vertex at a time.
#include "solve/ordering_refine.h"

#include <algorithm>
#include <cstdlib>

namespace intrinsic::detail {

// A max-heap of vertices by gain (smaller key first among equal gains, for
// determinism: the vertex's id in the whole graph), with each vertex's
// position for updates.
class SeparatorRefiner::Heap {
 public:
  Heap(std::vector<int>& pos, const int* key) : pos_(pos), key_(key) {}
  bool empty() const { return items_.empty(); }
  int top() const { return items_[0].vertex; }
  int top_gain() const { return items_[0].gain; }
  bool contains(int v) const { return pos_[v] >= 0; }
  void push(int v, int gain) {
    items_.push_back({gain, key_ ? key_[v] : v, v});
    pos_[v] = static_cast<int>(items_.size()) - 1;
    up(pos_[v]);
  }
  void update(int v, int gain) {
    const int i = pos_[v];
    const int old = items_[i].gain;
    items_[i].gain = gain;
    if (gain > old) up(i);
    else down(i);
  }
  void remove(int v) {
    const int i = pos_[v];
    pos_[v] = -1;
    const Item last = items_.back();
    items_.pop_back();
    if (i == static_cast<int>(items_.size())) return;
    items_[i] = last;
    pos_[last.vertex] = i;
    up(i);
    down(pos_[last.vertex]);
  }
  void clear() {
    for (const Item& it : items_) pos_[it.vertex] = -1;
    items_.clear();
  }

 private:
  struct Item {
    int gain, key, vertex;
  };
  static bool before(const Item& a, const Item& b) {
    return a.gain > b.gain || (a.gain == b.gain && a.key < b.key);
  }
  void place(int i, const Item& it) {
    items_[i] = it;
    pos_[it.vertex] = i;
  }
  void up(int i) {
    const Item it = items_[i];
    while (i > 0 && before(it, items_[(i - 1) / 2])) {
      place(i, items_[(i - 1) / 2]);
      i = (i - 1) / 2;
    }
    place(i, it);
  }
  void down(int i) {
    const Item it = items_[i];
    const int size = static_cast<int>(items_.size());
    for (;;) {
      int c = 2 * i + 1;
      if (c >= size) break;
      if (c + 1 < size && before(items_[c + 1], items_[c])) ++c;
      if (!before(items_[c], it)) break;
      place(i, items_[c]);
      i = c;
    }
    place(i, it);
  }
  std::vector<int>& pos_;
  const int* key_;
  std::vector<Item> items_;
};

SeparatorRefiner::SeparatorRefiner(const int* begin, const int* end, const int* index, int n)
    : begin_(begin), end_(end), index_(index), in0_(n, 0), in1_(n, 0), moved_(n, 0), pos0_(n, -1), pos1_(n, -1) {}

void SeparatorRefiner::bind(const int* begin, const int* end, const int* index, const int* key, int n) {
  begin_ = begin;
  end_ = end;
  index_ = index;
  key_ = key;
  // Between passes moved_ is 0 and pos -1 everywhere (pass() restores them),
  // so a longer graph only needs its new entries set.
  if (static_cast<int>(in0_.size()) < n) {
    in0_.resize(n, 0);
    in1_.resize(n, 0);
    moved_.resize(n, 0);
    pos0_.resize(n, -1);
    pos1_.resize(n, -1);
  }
}

namespace {

bool balanced(long w0, long w1, double max_fraction) {
  return std::max(w0, w1) <= max_fraction * static_cast<double>(w0 + w1);
}

// Whether separator state a (sizes of side 0, side 1, separator) beats b:
// balanced first, then the smaller separator, then the better balance.
bool better(const long a[3], const long b[3], double max_fraction) {
  const bool ba = balanced(a[0], a[1], max_fraction), bb = balanced(b[0], b[1], max_fraction);
  if (ba != bb) return ba;
  if (a[2] != b[2]) return a[2] < b[2];
  return std::labs(a[0] - a[1]) < std::labs(b[0] - b[1]);
}

}  // namespace

void SeparatorRefiner::refine(std::vector<int>& separator, signed char* side, const int* owner, int tag,
                              long size0, long size1, double max_fraction, int passes) {
  long weight[3] = {size0, size1, static_cast<long>(separator.size())};
  for (int p = 0; p < passes && !separator.empty(); ++p)
    if (!pass(separator, side, owner, tag, weight, max_fraction)) break;
}

// One pass; returns whether it improved the separator.
bool SeparatorRefiner::pass(std::vector<int>& separator, signed char* side, const int* owner, int tag,
                            long weight[3], double max_fraction) {
  Heap heap[2] = {Heap(pos0_, key_), Heap(pos1_, key_)};
  for (int v : separator) {
    in0_[v] = in1_[v] = 0;
    for (int k = begin_[v], e = end_of(v); k < e; ++k) {
      const int w = index_[k];
      if (owner[w] == tag && side[w] < 2) ++(side[w] == 0 ? in0_ : in1_)[v];
    }
    heap[0].push(v, 1 - in1_[v]);
    heap[1].push(v, 1 - in0_[v]);
  }
  moves_.clear();
  pulled_.clear();
  long best[3] = {weight[0], weight[1], weight[2]};
  size_t best_moves = 0;
  // Moves without a new best before giving up (METIS's bound, about).
  const long patience = std::min<long>(std::max<long>(weight[2], 5), 300);
  long bad = 0;
  while (bad <= patience) {
    const int to = pick_side(heap, weight, max_fraction);
    if (to < 0) break;
    move(heap[to].top(), to, heap, side, owner, tag, weight);
    // Only a smaller separator (or reaching balance) renews the patience:
    // moves that just even out the halves could walk the separator across
    // the whole piece one vertex at a time.
    const bool progress = weight[2] < best[2] || (balanced(weight[0], weight[1], max_fraction) &&
                                                  !balanced(best[0], best[1], max_fraction));
    if (better(weight, best, max_fraction)) {
      std::copy(weight, weight + 3, best);
      best_moves = moves_.size();
    }
    bad = progress ? 0 : bad + 1;
  }
  heap[0].clear();
  heap[1].clear();
  finish(separator, side, weight, best, best_moves);
  return best_moves > 0;
}

int SeparatorRefiner::pick_side(Heap heap[2], const long weight[3], double max_fraction) const {
  const std::vector<int>* in[2] = {&in0_, &in1_};
  int to = -1;
  for (int t = 0; t < 2; ++t) {
    if (heap[t].empty()) continue;
    const int v = heap[t].top();
    long after[2] = {weight[0], weight[1]};
    after[t] += 1;
    after[1 - t] -= (*in[1 - t])[v];
    const bool ok = balanced(after[0], after[1], max_fraction) ||
                    std::labs(after[0] - after[1]) <= std::labs(weight[0] - weight[1]);
    if (!ok) continue;
    if (to < 0 || heap[t].top_gain() > heap[to].top_gain() ||
        (heap[t].top_gain() == heap[to].top_gain() && weight[t] < weight[to]))
      to = t;
  }
  return to;
}

void SeparatorRefiner::move(int v, int to, Heap heap[2], signed char* side, const int* owner, int tag,
                            long weight[3]) {
  std::vector<int>* in[2] = {&in0_, &in1_};
  const int other = 1 - to;
  heap[0].remove(v);
  heap[1].remove(v);
  moved_[v] = 1;
  side[v] = static_cast<signed char>(to);
  ++weight[to];
  --weight[2];
  for (int k = begin_[v], e = end_of(v); k < e; ++k) {
    const int u = index_[k];
    if (owner[u] != tag) continue;
    if (side[u] == 2) {
      // u gained a neighbour in half `to`: moving u to `other` now pulls one more.
      ++(*in[to])[u];
      if (heap[other].contains(u)) heap[other].update(u, 1 - (*in[to])[u]);
    } else if (side[u] == other) {
      side[u] = 2;
      --weight[other];
      ++weight[2];
      pulled_.push_back(u);
      in0_[u] = in1_[u] = 0;
      for (int j = begin_[u], f = end_of(u); j < f; ++j) {
        const int w = index_[j];
        if (owner[w] != tag) continue;
        if (side[w] < 2) {
          ++(side[w] == 0 ? in0_ : in1_)[u];
        } else if (w != u) {
          // w lost a neighbour in `other`: moving w to `to` pulls one fewer.
          --(*in[other])[w];
          if (heap[to].contains(w)) heap[to].update(w, 1 - (*in[other])[w]);
        }
      }
      if (!moved_[u]) {
        heap[0].push(u, 1 - in1_[u]);
        heap[1].push(u, 1 - in0_[u]);
      }
    }
  }
  moves_.push_back({v, static_cast<signed char>(to), static_cast<int>(pulled_.size())});
}

void SeparatorRefiner::finish(std::vector<int>& separator, signed char* side, long weight[3], const long best[3],
                              size_t best_moves) {
  // Undo the moves after the best state, newest first.
  for (size_t m = moves_.size(); m-- > best_moves;) {
    const int from = m == 0 ? 0 : moves_[m - 1].pulled_end;
    for (int i = moves_[m].pulled_end; i-- > from;) side[pulled_[i]] = static_cast<signed char>(1 - moves_[m].to);
    side[moves_[m].vertex] = 2;
  }
  std::copy(best, best + 3, weight);
  // The new separator: the old one's vertices still in it and those pulled in.
  const int kept_pulled = best_moves == 0 ? 0 : moves_[best_moves - 1].pulled_end;
  for (const Move& m : moves_) moved_[m.vertex] = 0;
  std::vector<int> next;
  next.reserve(static_cast<size_t>(weight[2]));
  auto keep = [&](int v) {
    if (side[v] == 2 && !moved_[v]) {
      moved_[v] = 1;
      next.push_back(v);
    }
  };
  for (int v : separator) keep(v);
  for (int i = 0; i < kept_pulled; ++i) keep(pulled_[i]);
  for (int v : next) moved_[v] = 0;
  separator.swap(next);
}

}  // namespace intrinsic::detail
