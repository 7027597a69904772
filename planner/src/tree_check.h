/*
 * tree_check.h - internal: the search tree's invariants, checked whole (tree_check.c). The loop
 * asserts them at the end of every gmmrrt_planner_run when built with GMMRRT_TREE_CHECKS (Debug
 * and sanitizer builds); the planner.tree_check test calls the check directly on trees of every
 * planner kind and on trees broken on purpose. Not a public header.
 */
#ifndef GMMRRT_TREE_CHECK_H
#define GMMRRT_TREE_CHECK_H

#include <stddef.h>

struct gmmrrt_planner;

/* 1 when the tree of p holds every invariant, else 0 with the first broken one, naming the node,
 * in why[cap] (why may be NULL). The invariants:
 *   - the root (node 0) has no parent and a finite cost; every other node's parent is a node;
 *   - following parents from any node reaches the root (no cycle);
 *   - each node's child list holds exactly the nodes whose parent it is, each once;
 *   - cost(child) = cost(parent) + edge cost (gmmrrt_edge_cost), to a relative 1e-9 (sums of
 *     rewiring's cost shifts round in the last bits), and so cost(child) >= cost(parent);
 *   - every edge is collision-free (gmmrrt_planner_segment_free).
 * Reads the tree only; allocates nothing. */
int gmmrrt_tree_check(const struct gmmrrt_planner *p, char *why, size_t cap);

#endif /* GMMRRT_TREE_CHECK_H */
