// The γ-neighborhood graph (Veltkamp, chapter 3) in 2D (edges) and 3D
// (triangles): γ(c0,c1) of Definitions 3.1/3.2 and γ([c0,c1],[c2,c3]) of
// Definition 3.3, for the full parameter range including c1 < 0.
//
// The pencil. The balls touching a simplex S (k vertices in kD) form a pencil
// parametrised by t ∈ [-1,1]: radius r(S)/(1-|t|), centre on the positive side
// A of S's hyperplane for t > 0, on side B for t < 0, t = ±1 the open
// half-spaces. A vertex p strictly on side A lies inside ball(t) iff t > t_p
// (t_p: the parameter of the ball through S and p); p on side B iff t < t_p.
// So every simplex has two numbers
//   hi = min t_p over side-A vertices (1 if none),
//   lo = max t_p over side-B vertices (-1 if none),
// and N_γ(c0,c1) is empty iff (t1 = c1, t0 = -c0, or the mirror -t0, -t1)
//   c1 ≥ 0 (union of balls):      lo ≤ min(t0,t1) and max(t0,t1) ≤ hi,
//   c1 < 0 (intersection, lens):  lo ≤ max(t0,t1) and min(t0,t1) ≤ hi.
// A vertex in the open simplex (interior of R) puts S in no graph. In 3D a
// vertex in S's plane strictly inside S's circumcircle but not in the open
// triangle lies in every finite ball of the pencil but in no half-space.
//
// Reading of Definition 3.3 ("the largest values c'0, c'1 such that N_γ is
// empty"). With a = hi (how far the ball may grow towards side A) and
// b = -lo (towards side B), the set of empty (c0,c1), |c0| ≤ |c1|, is
//   {c0 ≤ b, c1 ≤ a} ∪ {c0 ≤ a, c1 ≤ b},
// for both signs of c1 (Figures 3.8/3.9). We take c'1 = the largest c1 for
// which some N_γ(·,c1) is empty and c'0 = the largest c0 with N_γ(c0,c'1)
// empty; in closed form {c'0,c'1} = {a,b} ordered so that |c'0| ≤ |c'1|
// (c'1 ≥ 0 on a tie). With this reading Lemma 3.1 (c1 ≥ 0) and Lemma 3.2
// (c1 < 0: γ([c0,1],[c1,1]) ∪ γ([c1,1],[|c0|,1])) hold exactly, and c'1 ≥ 0
// iff S has an empty touching ball, i.e. γ([-1,1],[0,1]) is the Delaunay
// triangulation (all simplices on a common empty sphere when degenerate).
// Exception: in 3D a vertex coplanar with S inside its circumcircle (a
// degenerate, coplanar 4-tuple) leaves only half-spaces: then c' = (1,1) if
// both half-spaces are empty, (-1,1) if one is, else (max(a,b), -1); the
// fixed-parameter γ(c0,c1) is always evaluated from Definition 3.1 itself.
//
// Exactness. Side of the hyperplane, on-simplex tests, in-circumcircle and
// the sign of t_p (inside the smallest ball or not) are exact predicates, so
// the parameters -1, 0, 1 (half-spaces, smallest balls: CH, Gabriel, DT) are
// decided exactly, and ties lo = hi (co-spherical vertices on both sides) are
// detected exactly. |t_p| is a double construction: a vertex whose ball
// parameter is within rounding of a requested parameter is decided by doubles.
//
// Input. Duplicate positions (bit for bit) are merged: the first occurrence
// takes part, later copies are isolated vertices in no simplex. k vertices on
// a (k-2)-plane (collinear triples in 3D) are no simplex (Definition 3.1).
// Fewer than k distinct points give an empty graph. Non-finite coordinates
// and parameters outside [-1,1] throw scanstation::InvalidInput.
#pragma once

#include <Eigen/Core>

namespace scanstation {

/// Parameter intervals of γ([c0,c1],[c2,c3]) (Definition 3.3); each in
/// [-1,1] with c0 ≤ c1 and c2 ≤ c3. Default: γ([-1,1],[0,1]) = Delaunay.
struct GammaRange {
  double c0 = -1, c1 = 1, c2 = 0, c3 = 1;
};

/// γ(c0,c1) (Definitions 3.1, 3.2), |c0| ≤ |c1|, both in [-1,1].
/// V  #V by 2 positions           → E  #E by 2 edges, i < j, sorted rows
/// V  #V by 3 positions           → T  #T by 3 triangles, i < j < k, sorted
/// Cost: c1 ≥ 0: one Delaunay triangulation, O(1) per Delaunay simplex
/// (Theorem 3.2). c1 < 0: see gamma_values.
Eigen::MatrixX2i gamma_graph(const Eigen::MatrixX2d& V, double c0, double c1);
Eigen::MatrixX3i gamma_graph(const Eigen::MatrixX3d& V, double c0, double c1);

/// γ([c0,c1],[c2,c3]) (Definition 3.3), output as for the fixed form.
Eigen::MatrixX2i gamma_graph(const Eigen::MatrixX2d& V, const GammaRange& range);
Eigen::MatrixX3i gamma_graph(const Eigen::MatrixX3d& V, const GammaRange& range);

/// Every simplex whose largest empty c'1 is ≥ floor, with its (c'0, c'1).
/// V      #V by 2 (or 3) positions
/// floor  in [-1,1]
/// S      (output) #S by 2 (or 3) vertex indices, ascending in each row,
///        rows sorted
/// C      (output) #S by 2: c'0, c'1 of each row of S
/// Algorithm. floor ≥ 0: Delaunay triangulation (CGAL, Epick); lo and hi of
/// a Delaunay simplex come from the vertices opposite it in its ≤ 2 incident
/// cells, O(1) each (Theorem 3.2); co-spherical clusters of cells (and, in
/// 3D, hull facets on one circle) add all their k-subsets, each bounded by
/// the cluster's points and the apexes of the cells across its boundary,
/// O(m) for a cluster of m points (degenerate input only). The triangles of
/// a planar hull face with another point of the face in their circle
/// (Θ(m³) for a face of m points) belong only to neighbourhoods with a
/// half-space, so they are listed only when the query has one (γ(±1,1),
/// γ(·,-1), ranges reaching c'0 = -1 with c'1 = 1, or c'1 = -1; always here):
/// γ(0,0) of a 15×15×15 lattice took more than 300 s with them, 0.4 s
/// without (γ(-1,1) of that lattice is 11M triangles). Listed, each asks
/// the face's points only whether one lies in its open triangle (those in
/// its box), and the apexes behind the face for its pencil: the hull of
/// CGAL's cube-meshed.off (696k triangles) 157 s → 11.7 s. Likewise the
/// triangles of a co-spherical cluster with cluster points on both sides of
/// their plane have lo = hi exactly, so a fixed γ(c0,c1) with c1 ≥ 0 takes
/// them only when c0 = -c1; other fixed queries list only the triangles on
/// the faces of the cluster's polytope (510 integer points on one sphere:
/// γ(0,0.5) from more than 100 s to 0.22 s). Collinear input (2D)
/// gives the pairs of neighbours along the line, no triangulation. Total
/// O(N log N) (2D) / O(size of DT) (3D) for non-degenerate input.
/// floor < 0: additionally the simplices with no empty ball but an empty
/// symmetric lens N_γ(floor,floor) (c'1 < 0 needs that, Lemma 3.3). 2D:
/// every pair is screened by a Yao-cone test (a vertex q within 0.45·α of the
/// direction a→b and closer than |ab|/3.3 lies in the lens, α = asin(1-|floor|)),
/// O(N²·1) cheap work; survivors, and in 3D every non-collinear triple
/// (O(N³)), get an exact k-d tree query of the ball that holds both lens
/// balls, which finds the whole profile when c'1 < 0. Worst case
/// O(N^k · m) with m the vertices in that ball: at floor = -1 the lens is the
/// open simplex and this degrades to the O(N^{k+1}) brute force, whose
/// output is then Θ(N^k) anyway.
/// The fixed form γ(c0,c1) with -1 < c1 < 0 needs no profile of a lens
/// simplex: one k-d query per orientation of N_γ(c0,c1), stopping at the
/// first vertex inside, decides it (and the k-d walk tests only the points
/// inside the query region exactly). Measured with bench/gamma_bench (one
/// core, γ(0,-0.5), against the tests' brute force in the same run): 2D
/// uniform N = 500, 1000, 2000: 23, 70, 210 ms vs 0.22, 1.5, 10.5 s; 2D
/// circle with 1% noise: 57, 202, 654 ms vs 0.27, 1.7, 12.0 s; 3D uniform
/// N = 60, 120, 240: 12, 82, 685 ms vs 20, 214, 2439 ms; 3D sphere with 1%
/// noise (most triangles in the graph: 270k at N = 240): 20, 223, 1730 ms
/// vs 34, 459, 5137 ms. Before, every lens simplex's whole profile was
/// searched and every point of a visited k-d leaf tested exactly: the noisy
/// sphere took 217 ms, 2.7 s, 28.6 s, up to 5.6× the brute force. 3D still
/// enumerates every triple (no screen like 2D's Yao cones), one at a time:
/// the vertices of CGAL's cactus mesh (620 points, 39.6M triples, 40.7k
/// triangles in γ(0,-0.5)) take 9.5–10.5 s and 71 MB (845 MB when the
/// candidates were stored first). The vertex that blocked the previous
/// query of each kind is tried before the k-d walk, if the walk would
/// reach it (same answers): consecutive candidates share all but one
/// vertex. Against the walk alone (alternating runs): the cactus 12.0–13.2 s
/// → 9.5–10.5 s; gamma_bench 3D uniform 240 points 633–742 → 604–608 ms, 2D
/// noisy circle 2000 points 662–787 → 559–590 ms, the noisy sphere (most
/// triples in the graph, nothing blocks) unchanged within the noise.
/// Where a triple's time goes now: its pencil (circumcircle, normal) and
/// the exact side and power tests of the vertices tried. A screen of
/// pairs, as in 2D, does not carry over: in 3D the lenses of all triangles
/// on an edge have only a small ball around the edge's midpoint in common
/// (radius about |ab|/16 at floor -0.5 for triangles whose angle opposite
/// the edge is within 30°–150°), which chords through the inside of a
/// solid (the lenses of its cross-section triangles are empty) never hold.
void gamma_values(const Eigen::MatrixX2d& V, double floor, Eigen::MatrixX2i& S, Eigen::MatrixX2d& C);
void gamma_values(const Eigen::MatrixX3d& V, double floor, Eigen::MatrixX3i& S, Eigen::MatrixX2d& C);

/// The pencil bounds of every 2D simplex having an empty touching disc
/// (c'1 ≥ 0; the Delaunay edges plus co-circular chords).
/// E   (output) #E by 2 edges, i < j, sorted
/// LH  (output) #E by 2: lo, hi of each edge; side A is the left of i → j
/// Used by the chapter-2 graphs (Gabriel, α-shape, β_c-skeleton).
void gamma_pencil_bounds(const Eigen::MatrixX2d& V, Eigen::MatrixX2i& E, Eigen::MatrixX2d& LH);

}  // namespace scanstation
