// Vertex-separator refinement for the nested dissection (internal; see
// ordering.h). A breadth-first level is a separator, but a jagged one: it
// follows the search's distance, not the shortest way across the piece. A
// Fiduccia-Mattheyses pass (the vertex-separator form METIS uses for its
// nested dissection) moves separator vertices into one half and pulls their
// neighbours in the other half into the separator whenever that shrinks it,
// within a balance bound, and keeps the smallest separator seen. The
// separator's size is what the factorization pays for (its dense block costs
// size^3/3 flops), so each vertex taken off the top separators matters.
#pragma once

#include <cstddef>
#include <vector>

namespace intrinsic::detail {

class SeparatorRefiner {
 public:
  // The graph in compressed-column form (end non-null for an uncompressed
  // matrix, as in ordering.cpp); n vertices.
  SeparatorRefiner(const int* begin, const int* end, const int* index, int n);

  // Moves the refiner to another graph of n vertices (a piece's compact copy,
  // ordering.cpp), its per-vertex arrays growing if needed. key[v] (null:
  // v itself) breaks ties between equal gains, smallest first: given a
  // compact copy's vertices' ids in the whole graph, a refinement there
  // moves the same vertices as it would on the whole graph.
  void bind(const int* begin, const int* end, const int* index, const int* key, int n);

  // Improves the separator of one piece: the vertices w with owner[w] == tag,
  // side[w] = 0 or 1 (the halves) or 2 (the separator, listed in
  // `separator`). No edge joins side 0 to side 1 before or after. Keeps
  // max(|side 0|, |side 1|) <= max_fraction * (|side 0| + |side 1|) if the
  // start does. At most `passes` passes; each is linear in the vertices it
  // touches (near the separator) times log of the separator size.
  void refine(std::vector<int>& separator, signed char* side, const int* owner, int tag, long size0, long size1,
              double max_fraction, int passes);

 private:
  struct Move {
    int vertex;
    signed char to;
    int pulled_end;  // end of the vertices this move pulled into the separator
  };
  class Heap;

  bool pass(std::vector<int>& separator, signed char* side, const int* owner, int tag, long weight[3],
            double max_fraction);
  // pass()'s steps: the side the next move goes to (-1: none keeps the
  // balance), one move with its neighbours' gains updated, and the undo of
  // the moves after the best state with the new separator collected.
  int pick_side(Heap heap[2], const long weight[3], double max_fraction) const;
  void move(int v, int to, Heap heap[2], signed char* side, const int* owner, int tag, long weight[3]);
  void finish(std::vector<int>& separator, signed char* side, long weight[3], const long best[3], std::size_t best_moves);
  int end_of(int v) const { return end_ ? begin_[v] + end_[v] : begin_[v + 1]; }

  const int* begin_;
  const int* end_;
  const int* index_;
  const int* key_ = nullptr;
  // Per-vertex counts of a separator vertex's neighbours in side 0 and 1,
  // and whether it moved in this pass. Reused across pieces.
  std::vector<int> in0_, in1_;
  std::vector<char> moved_;
  std::vector<int> pos0_, pos1_;  // heap positions (-1: absent)
  std::vector<Move> moves_;
  std::vector<int> pulled_;
};

}  // namespace intrinsic::detail
