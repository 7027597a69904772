/*
 * tree_check.c - the search tree's invariants (tree_check.h): the index-linked pool's shape
 * (parent, first child, next sibling), cost-to-come consistent with the edge costs after
 * rewiring (Karaman & Frazzoli 2011: RRT* keeps every node's cost the cost of its tree path),
 * and collision-free edges. O(n * children) time; no allocation.
 */
#include "tree_check.h"

#include <math.h>
#include <stdio.h>

#include "planner_internal.h"

/* Relative tolerance of the cost identity: rewiring shifts a subtree's costs by a difference,
 * so a node's cost is a sum that rounds differently from cost(parent) + edge in the last bits. */
#define GMMRRT_TREE_COST_REL_TOL 1e-9

static int broken(char *why, size_t cap, const char *what, int32_t node)
{
    if (why != NULL && cap > 0)
        snprintf(why, cap, "node %d: %s", (int)node, what);
    return 0;
}

/* Whether `child` is in the child list of `parent` (walked at most n steps). */
static int listed(const gmmrrt_links_t *link, int32_t n, int32_t parent, int32_t child)
{
    int32_t steps = 0;
    for (int32_t c = link[parent].first_child; c >= 0 && c < n && steps <= n; c = link[c].next_sibling, ++steps)
        if (c == child)
            return 1;
    return 0;
}

int gmmrrt_tree_check(const struct gmmrrt_planner *p, char *why, size_t cap)
{
    if (p == NULL || !p->has_problem)
        return broken(why, cap, "no problem set", -1);
    const int32_t n = p->num_nodes;
    const gmmrrt_links_t *link = p->pool.link;
    if (n < 1 || n > p->cfg.max_nodes)
        return broken(why, cap, "node count outside 1..max_nodes", n);
    if (link[0].parent != -1 || !isfinite(p->pool.cost[0]))
        return broken(why, cap, "the root has a parent or a cost that is not finite", 0);
    int64_t listed_total = 0;
    for (int32_t v = 0; v < n; ++v) {
        /* The child list: every entry a node whose parent is v; no longer than the tree. */
        int32_t steps = 0;
        for (int32_t c = link[v].first_child; c != -1; c = link[c].next_sibling) {
            if (c < 1 || c >= n)
                return broken(why, cap, "child list holds an index that is not a node", v);
            if (link[c].parent != v)
                return broken(why, cap, "child list holds a node whose parent is another", v);
            if (++steps > n)
                return broken(why, cap, "child list loops", v);
        }
        listed_total += steps;
        if (v == 0)
            continue;
        const int32_t parent = link[v].parent;
        if (parent < 0 || parent >= n || parent == v)
            return broken(why, cap, "parent is not another node", v);
        if (!listed(link, n, parent, v))
            return broken(why, cap, "missing from its parent's child list", v);
        /* No cycle: the root within n steps. */
        int32_t up = v, hops = 0;
        while (up != 0 && hops <= n) {
            up = link[up].parent;
            if (up < 0 || up >= n)
                return broken(why, cap, "an ancestor's parent is not a node", v);
            ++hops;
        }
        if (up != 0)
            return broken(why, cap, "following parents never reaches the root (a cycle)", v);
        const gmmrrt_xy_t *a = &p->pool.xy[parent], *b = &p->pool.xy[v];
        const double edge = gmmrrt_edge_cost(p, a->x, a->y, b->x, b->y);
        const double want = p->pool.cost[parent] + edge;
        if (!(fabs(p->pool.cost[v] - want) <= GMMRRT_TREE_COST_REL_TOL * fmax(1.0, fabs(want))))
            return broken(why, cap, "cost is not its parent's cost plus the edge's", v);
        if (!(p->pool.cost[v] >= p->pool.cost[parent]))
            return broken(why, cap, "cost below its parent's", v);
        if (!gmmrrt_planner_segment_free(p, a->x, a->y, b->x, b->y))
            return broken(why, cap, "the edge from its parent is in collision", v);
    }
    if (listed_total != n - 1)
        return broken(why, cap, "the child lists do not hold every node once", -1);
    return 1;
}
