/* fracterra — core/topology.c: arc-node topology of a layer's rings (shared boundaries stored once)
 * and the rebuilding of rings from their arcs.
 *
 * Build, in O(total ring vertices) expected time:
 *  1. vertices become node ids through a hash table: exact coordinates when tol == 0, else greedy
 *     snapping to the nearest earlier node within tol, found in the 3 x 3 neighbouring cells of a
 *     grid of cell size tol (the node keeps the coordinates of its first vertex);
 *  2. each ring becomes its cyclic node sequence without consecutive repeats, and the set of
 *     undirected edges between consecutive nodes is collected (hash table again);
 *  3. a node is a junction if its number of distinct neighbours is not 2, or if some ring turns back
 *     on itself there (the tip of a spike); between junctions edges chain into arcs, and a cycle with
 *     no junction at all becomes one closed arc, started where the first ring walking it starts;
 *  4. each ring is cut, from its first junction, into the arcs it walks, forward or reversed.
 * Arcs are created in ring order, so the first ring walking an arc walks it forward.
 * Line parts, and rings that collapse to a single node, get no arc reference (nrings = 0).
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "internal.h"
#include "fracterra/core.h"

#include <limits.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#define NONE SIZE_MAX

/* ---- hash map (uint64, uint64) -> size_t, open addressing with linear probing ---------------- */

typedef struct {
    uint64_t a, b;
    size_t v; /* NONE: empty slot */
} hslot;

typedef struct {
    hslot *slots;
    size_t mask;
} hmap;

static uint64_t mix64(uint64_t z)
{
    z = (z ^ (z >> 30)) * UINT64_C(0xBF58476D1CE4E5B9);
    z = (z ^ (z >> 27)) * UINT64_C(0x94D049BB133111EB);
    return z ^ (z >> 31);
}

/* Room for max_entries keys at a load factor of at most one half; the map never grows. */
static int hmap_init(hmap *m, size_t max_entries)
{
    size_t cap = 16;
    while (cap < 2 * max_entries) {
        if (cap > SIZE_MAX / 4)
            return ft_error(FT_E_NOMEM, "topology: hash table for %zu entries overflows", max_entries);
        cap *= 2;
    }
    m->slots = ft_realloc_array(NULL, cap, sizeof *m->slots);
    if (m->slots == NULL)
        return FT_E_NOMEM;
    for (size_t i = 0; i < cap; i++)
        m->slots[i].v = NONE;
    m->mask = cap - 1;
    return FT_OK;
}

static hslot *hmap_probe(const hmap *m, uint64_t a, uint64_t b)
{
    size_t i = (size_t)mix64(a ^ mix64(b + UINT64_C(0x9E3779B97F4A7C15))) & m->mask;
    while (m->slots[i].v != NONE && (m->slots[i].a != a || m->slots[i].b != b))
        i = (i + 1) & m->mask;
    return &m->slots[i];
}

static size_t hmap_get(const hmap *m, uint64_t a, uint64_t b)
{
    return hmap_probe(m, a, b)->v;
}

/* The value slot of key (a, b), created holding NONE if absent. */
static size_t *hmap_slot(hmap *m, uint64_t a, uint64_t b)
{
    hslot *s = hmap_probe(m, a, b);
    if (s->v == NONE) {
        s->a = a;
        s->b = b;
    }
    return &s->v;
}

/* ---- builder state ----------------------------------------------------------------------------- */

typedef struct {
    const ft_layer *l;
    double tol;
    size_t nverts; /* ring vertices over all ring parts (an upper bound on nodes and edges) */

    hmap vmap;        /* coordinates (tol == 0) or grid cell (tol > 0) -> node (head of the cell's list) */
    double *nx, *ny;  /* node coordinates */
    size_t *nnext;    /* next node in the same cell (tol > 0) */
    size_t nnodes;

    size_t *seq, *redge;      /* per ring position: node, and edge to the next position */
    size_t *seq_off, *seq_len; /* per part */

    hmap emap;           /* (min node, max node) -> edge */
    size_t *eu, *ev;     /* edge end nodes */
    size_t *e_arc, *e_pos;
    size_t nedges;

    size_t *deg;         /* distinct neighbours per node */
    unsigned char *junction;
    size_t *adj_off, *adj; /* incident edges per node (CSR) */

    size_t *arc_off, *arc_len, *arc_nodes; /* arc a: arc_len edges, nodes arc_nodes[arc_off ..] */
    unsigned char *arc_closed;
    size_t narcs, arc_nodes_used;

    ft_arc_ref *refs; /* per part, refs[seq_off[p] ..] (a ring has at most as many refs as edges) */
    size_t *nrefs;
} builder;

static void builder_free(builder *b)
{
    void *arrays[] = {b->vmap.slots, b->nx, b->ny, b->nnext, b->seq, b->redge, b->seq_off, b->seq_len,
                      b->emap.slots, b->eu, b->ev, b->e_arc, b->e_pos, b->deg, b->junction, b->adj_off,
                      b->adj, b->arc_off, b->arc_len, b->arc_nodes, b->arc_closed, b->refs, b->nrefs};
    for (size_t i = 0; i < sizeof arrays / sizeof arrays[0]; i++)
        free(arrays[i]);
}

static int is_ring(const ft_part *p)
{
    return (p->role == FT_ROLE_OUTER || p->role == FT_ROLE_INNER) && p->chain != NULL;
}

/* Counts ring vertices and checks their coordinates. */
static int count_ring_vertices(builder *b)
{
    const ft_layer *l = b->l;
    for (size_t p = 0; p < l->nparts; p++) {
        if (!is_ring(&l->parts[p]))
            continue;
        const ft_chain *c = l->parts[p].chain;
        for (size_t i = 0; i < c->n; i++)
            if (!isfinite(c->x[i]) || !isfinite(c->y[i]))
                return ft_error(FT_E_NUMERIC, "topology: feature %zu, part %zu, vertex %zu is not finite "
                                "(x=%g, y=%g)", l->parts[p].feature, p, i, c->x[i], c->y[i]);
        b->nverts += c->n;
    }
    return FT_OK;
}

#define ALLOC(ptr, n) (((ptr) = ft_realloc_array(NULL, (n) != 0 ? (n) : 1, sizeof *(ptr))) == NULL)

static int builder_alloc(builder *b)
{
    size_t nv = b->nverts, np = b->l->nparts;
    if (ALLOC(b->nx, nv) || ALLOC(b->ny, nv) || ALLOC(b->nnext, nv) || ALLOC(b->seq, nv) ||
        ALLOC(b->redge, nv) || ALLOC(b->seq_off, np) || ALLOC(b->seq_len, np) || ALLOC(b->eu, nv) ||
        ALLOC(b->ev, nv) || ALLOC(b->e_arc, nv) || ALLOC(b->e_pos, nv) || ALLOC(b->refs, nv) ||
        ALLOC(b->nrefs, np))
        return FT_E_NOMEM;
    int rc = hmap_init(&b->vmap, nv);
    if (rc == FT_OK)
        rc = hmap_init(&b->emap, nv);
    return rc;
}

/* ---- 1. vertices -> nodes ---------------------------------------------------------------------- */

static size_t new_node(builder *b, double x, double y)
{
    size_t n = b->nnodes++;
    b->nx[n] = x;
    b->ny[n] = y;
    b->nnext[n] = NONE;
    return n;
}

static size_t node_exact(builder *b, double x, double y)
{
    uint64_t kx, ky;
    x = (x == 0.0) ? 0.0 : x; /* -0.0 and 0.0 are the same place */
    y = (y == 0.0) ? 0.0 : y;
    memcpy(&kx, &x, sizeof kx);
    memcpy(&ky, &y, sizeof ky);
    size_t *v = hmap_slot(&b->vmap, kx, ky);
    if (*v == NONE)
        *v = new_node(b, x, y);
    return *v;
}

/* The nearest existing node within tol in the 3 x 3 cells around (x, y), else a new node. */
static int node_snapped(builder *b, double x, double y, size_t *out)
{
    double fx = floor(x / b->tol), fy = floor(y / b->tol);
    if (!(fabs(fx) < 4.0e18 && fabs(fy) < 4.0e18))
        return ft_error(FT_E_INVALID, "topology: tolerance %g is too small for coordinates (%g, %g)", b->tol,
                        x, y);
    int64_t cx = (int64_t)fx, cy = (int64_t)fy;
    size_t best = NONE;
    double bestd = b->tol * b->tol;
    for (int64_t dx = -1; dx <= 1; dx++)
        for (int64_t dy = -1; dy <= 1; dy++)
            for (size_t n = hmap_get(&b->vmap, (uint64_t)(cx + dx), (uint64_t)(cy + dy)); n != NONE;
                 n = b->nnext[n]) {
                double d = (b->nx[n] - x) * (b->nx[n] - x) + (b->ny[n] - y) * (b->ny[n] - y);
                if (d <= bestd && (best == NONE || d < bestd)) {
                    best = n;
                    bestd = d;
                }
            }
    if (best == NONE) {
        best = new_node(b, x, y);
        size_t *head = hmap_slot(&b->vmap, (uint64_t)cx, (uint64_t)cy);
        b->nnext[best] = *head;
        *head = best;
    }
    *out = best;
    return FT_OK;
}

/* Each ring's cyclic node sequence, without consecutive repeats (nor a repeated closing node). */
static int build_sequences(builder *b)
{
    size_t used = 0;
    for (size_t p = 0; p < b->l->nparts; p++) {
        b->seq_off[p] = used;
        b->seq_len[p] = 0;
        if (!is_ring(&b->l->parts[p]))
            continue;
        const ft_chain *c = b->l->parts[p].chain;
        size_t *s = b->seq + used, m = 0;
        for (size_t i = 0; i < c->n; i++) {
            size_t node = NONE;
            if (b->tol > 0.0) {
                int rc = node_snapped(b, c->x[i], c->y[i], &node);
                if (rc != FT_OK)
                    return rc;
            } else {
                node = node_exact(b, c->x[i], c->y[i]);
            }
            if (m == 0 || s[m - 1] != node)
                s[m++] = node;
        }
        while (m > 1 && s[m - 1] == s[0])
            m--;
        b->seq_len[p] = m;
        used += m;
    }
    return FT_OK;
}

/* ---- 2-3. edges, junctions, adjacency ------------------------------------------------------------ */

static void build_edges(builder *b)
{
    for (size_t p = 0; p < b->l->nparts; p++) {
        size_t m = b->seq_len[p], *s = b->seq + b->seq_off[p], *re = b->redge + b->seq_off[p];
        for (size_t i = 0; m >= 2 && i < m; i++) {
            size_t u = s[i], v = s[(i + 1) % m];
            size_t lo = u < v ? u : v, hi = u < v ? v : u;
            size_t *e = hmap_slot(&b->emap, lo, hi);
            if (*e == NONE) {
                *e = b->nedges++;
                b->eu[*e] = lo;
                b->ev[*e] = hi;
                b->e_arc[*e] = NONE;
                b->deg[lo]++;
                b->deg[hi]++;
            }
            re[i] = *e;
        }
    }
}

static int build_junctions(builder *b)
{
    size_t nn = b->nnodes;
    if (ALLOC(b->junction, nn) || ALLOC(b->adj_off, nn + 1) || ALLOC(b->adj, 2 * b->nedges))
        return FT_E_NOMEM;
    for (size_t n = 0; n < nn; n++)
        b->junction[n] = b->deg[n] != 2;
    for (size_t p = 0; p < b->l->nparts; p++) {
        size_t m = b->seq_len[p], *s = b->seq + b->seq_off[p];
        for (size_t i = 0; m >= 2 && i < m; i++)
            if (s[(i + m - 1) % m] == s[(i + 1) % m])
                b->junction[s[i]] = 1; /* the ring turns back here */
    }
    b->adj_off[0] = 0;
    for (size_t n = 0; n < nn; n++)
        b->adj_off[n + 1] = b->adj_off[n] + b->deg[n];
    for (size_t n = 0; n < nn; n++)
        b->deg[n] = 0; /* reused as the fill cursor; equals the degree again afterwards */
    for (size_t e = 0; e < b->nedges; e++) {
        b->adj[b->adj_off[b->eu[e]] + b->deg[b->eu[e]]++] = e;
        b->adj[b->adj_off[b->ev[e]] + b->deg[b->ev[e]]++] = e;
    }
    return FT_OK;
}

/* ---- 3-4. arcs and ring references --------------------------------------------------------------- */

static size_t other_end(const builder *b, size_t e, size_t n)
{
    return b->eu[e] == n ? b->ev[e] : b->eu[e];
}

/* The edge of a two-edge node that is not e. */
static size_t other_edge(const builder *b, size_t n, size_t e)
{
    const size_t *a = b->adj + b->adj_off[n];
    return a[0] == e ? a[1] : a[0];
}

/* Walks a new arc from node `start` through edge e until a junction (open arc) or, when the ring
 * holds no junction, back to `start` (closed arc). */
static int walk_arc(builder *b, size_t start, size_t e, int closed)
{
    size_t a = b->narcs++, cur = start, len = 0;
    b->arc_off[a] = b->arc_nodes_used;
    b->arc_closed[a] = (unsigned char)closed;
    for (;;) {
        if (b->e_arc[e] != NONE)
            return ft_error(FT_E_NUMERIC, "topology: edge %zu reached twice while tracing arc %zu", e, a);
        b->e_arc[e] = a;
        b->e_pos[e] = len++;
        b->arc_nodes[b->arc_nodes_used++] = cur;
        size_t next = other_end(b, e, cur);
        if (closed ? next == start : b->junction[next] != 0) {
            if (!closed)
                b->arc_nodes[b->arc_nodes_used++] = next;
            break;
        }
        e = other_edge(b, next, e);
        cur = next;
    }
    b->arc_len[a] = len;
    return FT_OK;
}

/* Cuts ring p into arc references, creating the arcs it is the first to walk. */
static int ring_refs(builder *b, size_t p)
{
    size_t m = b->seq_len[p], off = b->seq_off[p], *s = b->seq + off, *re = b->redge + off;
    size_t k = 0;
    while (k < m && !b->junction[s[k]])
        k++;
    int closed = k == m;
    if (closed)
        k = 0;
    ft_arc_ref *refs = b->refs + off;
    size_t nrefs = 0;
    for (size_t i = 0; i < m;) {
        size_t idx = (k + i) % m, u = s[idx], e = re[idx];
        if (b->e_arc[e] == NONE) {
            int rc = walk_arc(b, u, e, closed);
            if (rc != FT_OK)
                return rc;
        }
        size_t a = b->e_arc[e], pos = b->e_pos[e], len = b->arc_len[a];
        int fwd = b->arc_nodes[b->arc_off[a] + pos] == u;
        int aligned = b->arc_closed[a] ? closed : (fwd ? pos == 0 : pos + 1 == len);
        for (size_t j = 1; aligned && j < len; j++)
            aligned = i + j < m && b->e_arc[re[(idx + j) % m]] == a;
        if (!aligned)
            return ft_error(FT_E_NUMERIC, "topology: part %zu leaves arc %zu between its nodes", p, a);
        refs[nrefs].arc = a;
        refs[nrefs].reversed = !fwd;
        nrefs++;
        i += len;
    }
    b->nrefs[p] = nrefs;
    return FT_OK;
}

static int build_arcs(builder *b)
{
    size_t ne = b->nedges;
    if (ALLOC(b->arc_off, ne) || ALLOC(b->arc_len, ne) || ALLOC(b->arc_closed, ne) ||
        ALLOC(b->arc_nodes, 2 * ne))
        return FT_E_NOMEM;
    for (size_t p = 0; p < b->l->nparts; p++) {
        b->nrefs[p] = 0;
        if (b->seq_len[p] < 2)
            continue;
        int rc = ring_refs(b, p);
        if (rc != FT_OK)
            return rc;
    }
    return FT_OK;
}

/* ---- output -------------------------------------------------------------------------------------- */

/* Signed area of ring p's node sequence, relative to its first node. */
static double ring_area(const builder *b, size_t p)
{
    size_t m = b->seq_len[p];
    const size_t *s = b->seq + b->seq_off[p];
    double x0 = b->nx[s[0]], y0 = b->ny[s[0]], twice = 0.0;
    for (size_t i = 1; i + 1 < m; i++)
        twice += (b->nx[s[i]] - x0) * (b->ny[s[i + 1]] - y0) - (b->nx[s[i + 1]] - x0) * (b->ny[s[i]] - y0);
    return 0.5 * twice;
}

/* The part's region lies left of a ring walked counter-clockwise, except for holes, whose polygon
 * lies outside them. Each side keeps the first part that claims it. */
static void assign_sides(const builder *b, ft_topology *t)
{
    for (size_t a = 0; a < t->narcs; a++)
        t->arc_left[a] = t->arc_right[a] = -1;
    for (size_t p = 0; p < t->nparts; p++) {
        if (b->nrefs[p] == 0)
            continue;
        double area = ring_area(b, p);
        if (area == 0.0)
            continue;
        int region_left = (area > 0.0) != (b->l->parts[p].role == FT_ROLE_INNER);
        for (size_t r = 0; r < b->nrefs[p]; r++) {
            const ft_arc_ref *ref = &t->rings[p][r];
            int *side = (region_left != (ref->reversed != 0)) ? &t->arc_left[ref->arc] : &t->arc_right[ref->arc];
            if (*side == -1)
                *side = (int)p;
        }
    }
}

static ft_chain *arc_chain(const builder *b, size_t a)
{
    size_t nv = b->arc_closed[a] ? b->arc_len[a] : b->arc_len[a] + 1;
    const size_t *nodes = b->arc_nodes + b->arc_off[a];
    ft_chain *c = ft_chain_create(nv, b->arc_closed[a]);
    if (c == NULL)
        return NULL;
    for (size_t i = 0; i < nv; i++) {
        c->x[i] = b->nx[nodes[i]];
        c->y[i] = b->ny[nodes[i]];
    }
    c->n = nv;
    return c;
}

static ft_topology *make_topology(const builder *b)
{
    ft_topology *t = ft_calloc(1, sizeof *t);
    if (t == NULL)
        return NULL;
    t->narcs = b->narcs;
    t->nparts = b->l->nparts;
    if ((t->arcs = ft_calloc(t->narcs, sizeof *t->arcs)) == NULL || ALLOC(t->arc_left, t->narcs) ||
        ALLOC(t->arc_right, t->narcs) || (t->rings = ft_calloc(t->nparts, sizeof *t->rings)) == NULL ||
        (t->nrings = ft_calloc(t->nparts, sizeof *t->nrings)) == NULL)
        goto fail;
    for (size_t a = 0; a < t->narcs; a++)
        if ((t->arcs[a] = arc_chain(b, a)) == NULL)
            goto fail;
    for (size_t p = 0; p < t->nparts; p++) {
        size_t n = b->nrefs[p];
        if (n == 0)
            continue;
        if (ALLOC(t->rings[p], n))
            goto fail;
        memcpy(t->rings[p], b->refs + b->seq_off[p], n * sizeof *t->rings[p]);
        t->nrings[p] = n;
    }
    assign_sides(b, t);
    return t;
fail:
    ft_topology_free(t);
    return NULL;
}

int ft_layer_build_topology(ft_layer *l, double tol)
{
    if (l == NULL)
        return ft_error(FT_E_INVALID, "ft_layer_build_topology: NULL layer");
    if (!(tol >= 0.0) || !isfinite(tol))
        return ft_error(FT_E_INVALID, "topology tolerance must be finite and >= 0, got %g", tol);
    if (l->nparts > INT_MAX)
        return ft_error(FT_E_INVALID, "topology: too many parts (%zu)", l->nparts);
    builder b;
    memset(&b, 0, sizeof b);
    b.l = l;
    b.tol = tol;
    int rc = count_ring_vertices(&b);
    if (rc == FT_OK)
        rc = builder_alloc(&b);
    if (rc == FT_OK)
        rc = build_sequences(&b);
    if (rc == FT_OK)
        rc = (b.deg = ft_calloc(b.nnodes ? b.nnodes : 1, sizeof *b.deg)) ? FT_OK : FT_E_NOMEM;
    if (rc == FT_OK) {
        build_edges(&b);
        rc = build_junctions(&b);
    }
    if (rc == FT_OK)
        rc = build_arcs(&b);
    ft_topology *t = rc == FT_OK ? make_topology(&b) : NULL;
    if (rc == FT_OK && t == NULL)
        rc = FT_E_NOMEM;
    builder_free(&b);
    if (rc != FT_OK)
        return rc;
    ft_topology_free(l->topology);
    l->topology = t;
    return FT_OK;
}

/* ---- applying edited arcs ------------------------------------------------------------------------ */

/* Checks ring p's references against the arcs and returns the vertex count of its rebuilt chain. */
static int rebuilt_size(const ft_topology *t, size_t p, size_t *nv)
{
    *nv = 0;
    for (size_t r = 0; r < t->nrings[p]; r++) {
        size_t a = t->rings[p][r].arc;
        if (a >= t->narcs || t->arcs[a] == NULL)
            return ft_error(FT_E_INVALID, "topology: part %zu refers to arc %zu of %zu", p, a, t->narcs);
        const ft_chain *c = t->arcs[a];
        size_t min = c->closed ? 3 : 2;
        if (c->n < min)
            return ft_error(FT_E_INVALID, "topology: %s arc %zu has %zu vertices, at least %zu needed",
                            c->closed ? "closed" : "open", a, c->n, min);
        *nv += c->closed ? c->n : c->n - 1;
    }
    return FT_OK;
}

/* Appends arc a walked forward or backward, without its last vertex when open (the next arc starts
 * there); a closed arc walked backward still starts at its first vertex. */
static void append_arc(ft_chain *dst, const ft_chain *arc, int reversed)
{
    size_t n = arc->closed ? arc->n : arc->n - 1;
    for (size_t i = 0; i < n; i++) {
        size_t j = i;
        if (reversed)
            j = arc->closed ? (arc->n - i) % arc->n : arc->n - 1 - i;
        dst->x[dst->n] = arc->x[j];
        dst->y[dst->n] = arc->y[j];
        dst->n++;
    }
}

/* All rebuilt rings are made before any is replaced, so that a failure leaves the layer unchanged. */
int ft_layer_apply_topology(ft_layer *l)
{
    if (l == NULL)
        return ft_error(FT_E_INVALID, "ft_layer_apply_topology: NULL layer");
    const ft_topology *t = l->topology;
    if (t == NULL)
        return ft_error(FT_E_INVALID, "layer has no topology: call ft_layer_build_topology first");
    if (t->nparts != l->nparts)
        return ft_error(FT_E_INVALID, "topology describes %zu parts, the layer has %zu", t->nparts, l->nparts);
    ft_chain **fresh = ft_calloc(l->nparts ? l->nparts : 1, sizeof *fresh);
    if (fresh == NULL)
        return FT_E_NOMEM;
    int rc = FT_OK;
    for (size_t p = 0; p < l->nparts && rc == FT_OK; p++) {
        size_t nv;
        if (t->nrings[p] == 0 || (rc = rebuilt_size(t, p, &nv)) != FT_OK)
            continue;
        if ((fresh[p] = ft_chain_create(nv, 1)) == NULL) {
            rc = FT_E_NOMEM;
            break;
        }
        for (size_t r = 0; r < t->nrings[p]; r++)
            append_arc(fresh[p], t->arcs[t->rings[p][r].arc], t->rings[p][r].reversed);
    }
    for (size_t p = 0; p < l->nparts; p++) {
        if (fresh[p] == NULL)
            continue;
        if (rc == FT_OK) {
            ft_chain_free(l->parts[p].chain);
            l->parts[p].chain = fresh[p];
        } else {
            ft_chain_free(fresh[p]);
        }
    }
    free(fresh);
    return rc;
}

void ft_topology_free(ft_topology *t)
{
    if (t == NULL)
        return;
    for (size_t a = 0; t->arcs != NULL && a < t->narcs; a++)
        ft_chain_free(t->arcs[a]);
    for (size_t p = 0; t->rings != NULL && p < t->nparts; p++)
        free(t->rings[p]);
    free(t->arcs);
    free(t->arc_left);
    free(t->arc_right);
    free(t->rings);
    free(t->nrings);
    free(t);
}
