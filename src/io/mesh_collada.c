/*
 * mesh_collada.c: a Collada document checked before assimp reads it.
 *
 * assimp 5.2's Collada reader believes what a document says of itself, and
 * a file that lies crashes it or makes it take gigabytes: an index list
 * with a character that is not a number (it reads zeros for ever), a
 * primitive or weight count far beyond its indices (it reserves room for
 * them first), a negative count, an accessor that reaches past its array
 * or has more parameters than its stride (it reads beyond), a <p> without
 * a VERTEX input, a strip whose count is 0, a node that instances itself
 * (it recurses for ever), a hexadecimal image (it reads four times its
 * length).  So the whole document is read once here, with libxml2's
 * streaming reader, and refused naming the line of the first such thing.
 * A well-made file (Blender's, SketchUp's, 3ds Max's) passes unchanged.
 */
#include "io_internal.h"

#include <errno.h>
#include <limits.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <libxml/xmlreader.h>

#include "xml_errors.h"

/* Nodes instanced within nodes: more than this many, or this deep, is not a model. */
#define MAX_EXPANDED_NODES 100000
#define MAX_NODE_DEPTH 1000

/* Nodes an <instance_node> may name (ids and names are meant to be unique): more is a lie. */
#define MAX_INSTANCE_TARGETS 64

#define NO_NODE SIZE_MAX

/* An array of values an accessor may read: its id and how many values it holds. */
typedef struct {
    char *id;
    uint64_t values;
} value_array;

/* An accessor, to be checked against its array once the whole document is read. */
typedef struct {
    char *array; /* the array's id, without the '#' */
    uint64_t count, stride, offset, params;
    long line;
} accessor;

/* A <node>: its id and name (either may be NULL), the node it lies in, its line. */
typedef struct {
    char *id, *name;
    size_t parent;
    long line;
} scene_node;

/* An <instance_node url="#target"> inside node. */
typedef struct {
    size_t node;
    char *target;
    long line;
} node_instance;

/* Ways a primitive element lays out its indices, as assimp reads them. */
typedef enum { LAYOUT_TRIANGLES, LAYOUT_LINES, LAYOUT_POLYLIST, LAYOUT_ONE_PER_P } layout;

/* The primitive (or <vertex_weights>) element being read. */
typedef struct {
    bool open;
    int depth;
    long line;
    const char *name;
    layout layout;
    unsigned min_vertices; /* per <p>, for strips and fans */
    uint64_t count;
    uint64_t offsets; /* the largest input offset + 1 */
    bool has_vertex;  /* an input with semantic VERTEX came */
    uint64_t vcount_entries;
    uint64_t vcount_sum;    /* of the first count entries */
    uint64_t p_elements;    /* <p> and <ph> */
    uint64_t weight_values; /* the tokens of <v> */
} primitive;

typedef struct {
    const char *path;
    xmlTextReaderPtr reader;
    ur_error *error;
    value_array *arrays;
    size_t array_count, array_capacity;
    accessor *accessors;
    size_t accessor_count, accessor_capacity;
    int accessor_depth; /* of the accessor whose params are being counted, or -1 */
    scene_node *nodes;
    size_t node_count, node_capacity;
    size_t open_nodes[MAX_NODE_DEPTH]; /* the nodes the reader is inside */
    int open_node_depths[MAX_NODE_DEPTH];
    size_t open_node_count;
    node_instance *instances;
    size_t instance_count, instance_capacity;
    primitive primitive;
} checker;

/* ---- Small helpers ----------------------------------------------------- */

/*
 * items (count of them, room for *capacity) with room for one more: the
 * same block, or a larger one; NULL when out of memory, items then kept.
 */
static void *with_room(void *items, size_t *capacity, size_t count, size_t item_size)
{
    if (count < *capacity)
        return items;
    size_t wanted = *capacity ? 2 * *capacity : 16;
    void *bigger = realloc(items, wanted * item_size);
    if (bigger)
        *capacity = wanted;
    return bigger;
}

static long current_line(const checker *c)
{
    return xmlGetLineNo(xmlTextReaderCurrentNode(c->reader));
}

static ur_status refuse(const checker *c, long line, const char *what)
{
    return ur_error_set(c->error, UR_ERROR_INPUT, "%s:%ld: %s", c->path, line, what);
}

static ur_status out_of_memory(const checker *c)
{
    return ur_error_set(c->error, UR_ERROR_MEMORY, "%s: out of memory checking the Collada file",
                        c->path);
}

static bool is_space(char c)
{
    return c == ' ' || c == '\t' || c == '\n' || c == '\r';
}

/* The next word of text from *at, white space around it skipped; false when none is left. */
static bool next_word(const char **at, const char **word, size_t *length)
{
    const char *p = *at;
    while (is_space(*p))
        p++;
    if (*p == '\0')
        return false;
    *word = p;
    while (*p && !is_space(*p))
        p++;
    *length = (size_t)(p - *word);
    *at = p;
    return true;
}

/*
 * The attribute as a whole number of at most max, or fallback when it is
 * absent; UR_ERROR_INPUT naming the element and attribute otherwise.
 */
static ur_status number_attribute(const checker *c, const char *element, const char *name,
                                  uint64_t max, uint64_t fallback, uint64_t *value)
{
    *value = fallback;
    xmlChar *text = xmlTextReaderGetAttribute(c->reader, (const xmlChar *)name);
    if (!text)
        return UR_OK;
    const char *at = (const char *)text, *word = NULL;
    size_t length = 0;
    bool valid = next_word(&at, &word, &length) &&
                 io_whole_number(word, length, false, max, value) &&
                 !next_word(&at, &word, &length);
    ur_status status = UR_OK;
    if (!valid)
        status = ur_error_set(c->error, UR_ERROR_INPUT,
                              "%s:%ld: <%s %s=\"%.40s\">: not a whole number from 0 to %llu",
                              c->path, current_line(c), element, name, (const char *)text,
                              (unsigned long long)max);
    xmlFree(text);
    return status;
}

/*
 * A copy of the attribute's value into *copy (NULL when absent), without
 * its leading '#' when reference is set (NULL when it has none); false
 * only when out of memory.
 */
static bool copy_attribute(const checker *c, const char *name, bool reference, char **copy)
{
    xmlChar *text = xmlTextReaderGetAttribute(c->reader, (const xmlChar *)name);
    *copy = NULL;
    if (!text || (reference && text[0] != '#')) {
        xmlFree(text);
        return true;
    }
    *copy = strdup((const char *)text + (reference ? 1 : 0));
    xmlFree(text);
    return *copy != NULL;
}

/* ---- Lists of values --------------------------------------------------- */

typedef enum { WORDS_REAL, WORDS_INDEX, WORDS_COUNT, WORDS_ANY } word_kind;

/*
 * Counts the words of the element's text into *words, each checked to be
 * of kind (an index may be negative: assimp reads it as 0), and adds the
 * first sum_limit of them to *sum when sum is not NULL.
 */
static ur_status read_words(const checker *c, const char *element, word_kind kind, uint64_t *words,
                            uint64_t *sum, uint64_t sum_limit)
{
    *words = 0;
    xmlChar *text = xmlTextReaderReadString(c->reader);
    if (!text)
        return UR_OK; /* no text; libxml2's own errors show at the end */
    const char *at = (const char *)text, *word = NULL;
    size_t length = 0;
    ur_status status = UR_OK;
    while (status == UR_OK && next_word(&at, &word, &length)) {
        uint64_t value = 0;
        bool valid = kind == WORDS_ANY ||
                     (kind == WORDS_REAL && io_real_number(word, length, true)) ||
                     (kind != WORDS_REAL &&
                      io_whole_number(word, length, kind == WORDS_INDEX, INT_MAX, &value));
        if (!valid)
            status =
                ur_error_set(c->error, UR_ERROR_INPUT, "%s:%ld: <%s> holds '%.*s': not %s", c->path,
                             current_line(c), element, (int)(length > 40 ? 40 : length), word,
                             kind == WORDS_REAL ? "a number" : "a whole number");
        else if (sum && *words < sum_limit)
            *sum += value;
        (*words)++;
    }
    xmlFree(text);
    return status;
}

/* <float_array>, <Name_array>, <IDREF_array>: as many values as their count says. */
static ur_status check_array(checker *c, const char *element, word_kind kind)
{
    uint64_t count = 0, words = 0;
    ur_status status = number_attribute(c, element, "count", UINT_MAX, 0, &count);
    if (status == UR_OK)
        status = read_words(c, element, kind, &words, NULL, 0);
    if (status == UR_OK && words != count)
        status = ur_error_set(
            c->error, UR_ERROR_INPUT, "%s:%ld: <%s count=\"%llu\"> holds %llu values", c->path,
            current_line(c), element, (unsigned long long)count, (unsigned long long)words);
    char *id = NULL;
    if (status != UR_OK)
        return status;
    if (!copy_attribute(c, "id", false, &id))
        return out_of_memory(c);
    if (!id)
        return UR_OK;
    value_array *arrays = with_room(c->arrays, &c->array_capacity, c->array_count, sizeof *arrays);
    if (!arrays) {
        free(id);
        return out_of_memory(c);
    }
    c->arrays = arrays;
    c->arrays[c->array_count++] = (value_array){.id = id, .values = count};
    return UR_OK;
}

/* ---- Accessors --------------------------------------------------------- */

static ur_status open_accessor(checker *c, int depth)
{
    accessor a = {.line = current_line(c)};
    ur_status status = number_attribute(c, "accessor", "count", INT_MAX, 0, &a.count);
    if (status == UR_OK)
        status = number_attribute(c, "accessor", "stride", UINT_MAX, 1, &a.stride);
    if (status == UR_OK)
        status = number_attribute(c, "accessor", "offset", UINT_MAX, 0, &a.offset);
    if (status == UR_OK && a.stride == 0)
        status = refuse(c, a.line, "<accessor stride=\"0\">: a stride is at least 1");
    if (status != UR_OK)
        return status;
    if (!copy_attribute(c, "source", true, &a.array))
        return out_of_memory(c);
    if (!a.array)
        return UR_OK; /* assimp refuses a source that is not "#id" itself */
    accessor *accessors =
        with_room(c->accessors, &c->accessor_capacity, c->accessor_count, sizeof *accessors);
    if (!accessors) {
        free(a.array);
        return out_of_memory(c);
    }
    c->accessors = accessors;
    c->accessors[c->accessor_count++] = a;
    c->accessor_depth = depth;
    return UR_OK;
}

/* A <param> of the accessor being read: a float4x4 takes 16 values of a stride. */
static void count_param(checker *c)
{
    accessor *a = &c->accessors[c->accessor_count - 1];
    xmlChar *type = xmlTextReaderGetAttribute(c->reader, (const xmlChar *)"type");
    bool matrix = type && strcmp((const char *)type, "float4x4") == 0;
    xmlFree(type);
    a->params += matrix ? 16 : 1;
}

static int compare_arrays(const void *a, const void *b)
{
    return strcmp(((const value_array *)a)->id, ((const value_array *)b)->id);
}

/*
 * Arrays sorted by id, those that share one each taking the fewest values
 * of them: assimp keeps the last, which need not be the one found.
 */
static void sort_arrays(checker *c)
{
    if (c->array_count == 0)
        return; /* no array to sort: c->arrays is NULL, which qsort must not be given */
    qsort(c->arrays, c->array_count, sizeof *c->arrays, compare_arrays);
    size_t start = 0;
    for (size_t i = 1; i <= c->array_count; i++) {
        if (i < c->array_count && strcmp(c->arrays[i].id, c->arrays[start].id) == 0)
            continue;
        uint64_t fewest = c->arrays[start].values;
        for (size_t k = start; k < i; k++)
            fewest = c->arrays[k].values < fewest ? c->arrays[k].values : fewest;
        for (size_t k = start; k < i; k++)
            c->arrays[k].values = fewest;
        start = i;
    }
}

/* Every accessor within its array, its parameters within its stride. */
static ur_status check_accessors(checker *c)
{
    sort_arrays(c);
    for (size_t i = 0; i < c->accessor_count; i++) {
        const accessor *a = &c->accessors[i];
        char text[160];
        if (a->params > a->stride) {
            snprintf(text, sizeof text, "<accessor stride=\"%llu\"> has %llu parameter values",
                     (unsigned long long)a->stride, (unsigned long long)a->params);
            return refuse(c, a->line, text);
        }
        value_array key = {.id = a->array};
        const value_array *array = c->array_count ? bsearch(&key, c->arrays, c->array_count,
                                                            sizeof *c->arrays, compare_arrays)
                                                  : NULL;
        if (!array)
            continue; /* assimp refuses a reference it cannot resolve itself */
        uint64_t reach = a->offset + a->count * a->stride;
        if (reach > array->values) {
            snprintf(text, sizeof text,
                     "<accessor source=\"#%.40s\"> reaches value %llu of an array of %llu",
                     a->array, (unsigned long long)reach, (unsigned long long)array->values);
            return refuse(c, a->line, text);
        }
    }
    return UR_OK;
}

/* ---- Primitives and weights -------------------------------------------- */

static const struct {
    const char *name;
    layout layout;
    unsigned min_vertices;
} primitive_kinds[] = {
    {"triangles", LAYOUT_TRIANGLES, 0},  {"lines", LAYOUT_LINES, 0},
    {"polylist", LAYOUT_POLYLIST, 0},    {"polygons", LAYOUT_ONE_PER_P, 0},
    {"trifans", LAYOUT_ONE_PER_P, 3},    {"tristrips", LAYOUT_ONE_PER_P, 3},
    {"linestrips", LAYOUT_ONE_PER_P, 2}, {"vertex_weights", LAYOUT_POLYLIST, 0},
};

#define PRIMITIVE_KIND_COUNT (sizeof primitive_kinds / sizeof primitive_kinds[0])

static int primitive_kind(xmlTextReaderPtr reader)
{
    for (size_t i = 0; i < PRIMITIVE_KIND_COUNT; i++)
        if (io_reader_is(reader, primitive_kinds[i].name))
            return (int)i;
    return -1;
}

static bool is_weights(const primitive *p)
{
    return strcmp(p->name, "vertex_weights") == 0;
}

static ur_status open_primitive(checker *c, int kind, int depth)
{
    primitive *p = &c->primitive;
    *p = (primitive){.open = true,
                     .depth = depth,
                     .line = current_line(c),
                     .name = primitive_kinds[kind].name,
                     .layout = primitive_kinds[kind].layout,
                     .min_vertices = primitive_kinds[kind].min_vertices,
                     .offsets = 1};
    /* assimp takes a weights' count as an int, a primitive's as an unsigned int */
    return number_attribute(c, p->name, "count", is_weights(p) ? INT_MAX : UINT_MAX, 0, &p->count);
}

static ur_status read_input(checker *c)
{
    primitive *p = &c->primitive;
    uint64_t offset = 0;
    ur_status status = number_attribute(c, "input", "offset", INT_MAX, 0, &offset);
    if (status != UR_OK)
        return status;
    if (offset + 1 > p->offsets)
        p->offsets = offset + 1;
    xmlChar *semantic = xmlTextReaderGetAttribute(c->reader, (const xmlChar *)"semantic");
    if (semantic && strcmp((const char *)semantic, "VERTEX") == 0)
        p->has_vertex = true;
    xmlFree(semantic);
    return UR_OK;
}

static ur_status read_vcount(checker *c)
{
    primitive *p = &c->primitive;
    p->vcount_sum = 0;
    return read_words(c, "vcount", WORDS_COUNT, &p->vcount_entries, &p->vcount_sum, p->count);
}

/* How many indices a <p> of the primitive must hold, in words, for a message. */
static void describe_need(const primitive *p, char *text, size_t size)
{
    unsigned long long offsets = p->offsets;
    if (p->layout == LAYOUT_TRIANGLES)
        snprintf(text, size, "%llu", 3 * p->count * offsets);
    else if (p->layout == LAYOUT_LINES) /* as check_indices lets SketchUp's counts pass */
        snprintf(text, size, "at least %llu", p->count * offsets);
    else if (p->layout == LAYOUT_POLYLIST && p->vcount_entries != p->count)
        snprintf(text, size, "a <vcount> of %llu values (it has %llu)",
                 (unsigned long long)p->count, (unsigned long long)p->vcount_entries);
    else if (p->layout == LAYOUT_POLYLIST)
        snprintf(text, size, "%llu", p->vcount_sum * offsets);
    else
        snprintf(text, size, "a multiple of %llu, at least %llu", offsets,
                 p->min_vertices * offsets);
}

/* The indices of one <p>, in the numbers its primitive's layout asks for. */
static ur_status check_indices(checker *c, uint64_t words)
{
    primitive *p = &c->primitive;
    char text[300];
    if (!p->has_vertex) {
        snprintf(text, sizeof text, "<p> of <%s> before an <input semantic=\"VERTEX\">", p->name);
        return refuse(c, current_line(c), text);
    }
    uint64_t vertices = words / p->offsets;
    bool fits = words % p->offsets == 0;
    if (p->layout == LAYOUT_TRIANGLES)
        fits = fits && vertices == 3 * p->count;
    else if (p->layout == LAYOUT_LINES) /* SketchUp miscounts lines; assimp counts them again */
        fits = fits && p->count <= vertices;
    else if (p->layout == LAYOUT_POLYLIST)
        fits = fits && p->vcount_entries == p->count && vertices == p->vcount_sum;
    else
        fits = fits && vertices >= p->min_vertices;
    if (fits)
        return UR_OK;
    char need[120];
    describe_need(p, need, sizeof need);
    snprintf(text, sizeof text,
             "<p> holds %llu indices where <%s count=\"%llu\"> with %llu index%s per corner "
             "needs %s",
             (unsigned long long)words, p->name, (unsigned long long)p->count,
             (unsigned long long)p->offsets, p->offsets == 1 ? "" : "es", need);
    return refuse(c, current_line(c), text);
}

static ur_status read_p(checker *c)
{
    primitive *p = &c->primitive;
    uint64_t words = 0;
    p->p_elements++;
    ur_status status = read_words(c, "p", WORDS_INDEX, &words, NULL, 0);
    if (status == UR_OK && words > 0)
        status = check_indices(c, words);
    return status;
}

/* The end of a primitive or weights element: the counts its children gave. */
static ur_status close_primitive(checker *c)
{
    primitive *p = &c->primitive;
    p->open = false;
    char text[200];
    if (p->layout == LAYOUT_ONE_PER_P && p->count != p->p_elements) {
        snprintf(text, sizeof text, "<%s count=\"%llu\"> has %llu <p>", p->name,
                 (unsigned long long)p->count, (unsigned long long)p->p_elements);
        return refuse(c, p->line, text);
    }
    if (!is_weights(p) || p->count == 0)
        return UR_OK;
    /* assimp reads a joint and a weight per influence, whatever the inputs */
    if (p->vcount_entries != p->count || p->weight_values < 2 * p->vcount_sum) {
        snprintf(text, sizeof text,
                 "<vertex_weights count=\"%llu\">: %llu <vcount> values, %llu <v> values",
                 (unsigned long long)p->count, (unsigned long long)p->vcount_entries,
                 (unsigned long long)p->weight_values);
        return refuse(c, p->line, text);
    }
    return UR_OK;
}

/* An element inside the open primitive or weights element. */
static ur_status primitive_child(checker *c)
{
    primitive *p = &c->primitive;
    if (io_reader_is(c->reader, "input"))
        return read_input(c);
    if (io_reader_is(c->reader, "vcount"))
        return read_vcount(c);
    if (io_reader_is(c->reader, "ph"))
        p->p_elements++;
    if (io_reader_is(c->reader, "p") && !is_weights(p))
        return read_p(c);
    if (io_reader_is(c->reader, "v") && is_weights(p))
        return read_words(c, "v", WORDS_INDEX, &p->weight_values, NULL, 0);
    return UR_OK;
}

/* ---- Nodes ------------------------------------------------------------- */

static size_t innermost_node(const checker *c)
{
    return c->open_node_count ? c->open_nodes[c->open_node_count - 1] : NO_NODE;
}

static ur_status open_node(checker *c, int depth)
{
    if (c->open_node_count == MAX_NODE_DEPTH)
        return refuse(c, current_line(c), "nodes nested more than 1000 deep");
    scene_node *nodes = with_room(c->nodes, &c->node_capacity, c->node_count, sizeof *nodes);
    if (!nodes)
        return out_of_memory(c);
    c->nodes = nodes;
    scene_node *node = &c->nodes[c->node_count];
    *node = (scene_node){.parent = innermost_node(c), .line = current_line(c)};
    if (!copy_attribute(c, "id", false, &node->id) ||
        !copy_attribute(c, "name", false, &node->name)) {
        free(node->id);
        return out_of_memory(c);
    }
    c->open_nodes[c->open_node_count] = c->node_count++;
    c->open_node_depths[c->open_node_count++] = depth;
    return UR_OK;
}

static ur_status add_instance(checker *c)
{
    size_t node = innermost_node(c);
    char *target = NULL;
    if (node != NO_NODE && !copy_attribute(c, "url", true, &target))
        return out_of_memory(c);
    if (!target)
        return UR_OK; /* outside a node, or not "#id": assimp does not follow it */
    node_instance *instances =
        with_room(c->instances, &c->instance_capacity, c->instance_count, sizeof *instances);
    if (!instances) {
        free(target);
        return out_of_memory(c);
    }
    c->instances = instances;
    c->instances[c->instance_count++] =
        (node_instance){.node = node, .target = target, .line = current_line(c)};
    return UR_OK;
}

/* ---- The node graph: nested nodes and instanced ones ------------------- */

/* A key a node is found by: assimp looks an instance's target up by id, then by name. */
typedef struct {
    const char *key;
    size_t node;
} node_key;

typedef struct {
    size_t *first; /* per node, its first edge; node_count + 1 of them */
    size_t *to;
    node_key *keys;
    size_t key_count;
} node_graph;

/* By key, then node: a node whose id is its name (Blender writes them so) twice in a row. */
static int compare_keys(const void *a, const void *b)
{
    const node_key *x = a, *y = b;
    int order = strcmp(x->key, y->key);
    return order ? order : (x->node > y->node) - (x->node < y->node);
}

static void graph_free(node_graph *g)
{
    free(g->first);
    free(g->to);
    free(g->keys);
}

/* The nodes named target by id or name: keys[*begin, *end). */
static void find_keys(const node_graph *g, const char *target, size_t *begin, size_t *end)
{
    size_t low = 0, high = g->key_count;
    while (low < high) {
        size_t middle = low + (high - low) / 2;
        if (strcmp(g->keys[middle].key, target) < 0)
            low = middle + 1;
        else
            high = middle;
    }
    *begin = *end = low;
    while (*end < g->key_count && strcmp(g->keys[*end].key, target) == 0)
        (*end)++;
}

static bool make_keys(const checker *c, node_graph *g)
{
    g->keys = malloc((2 * c->node_count + 1) * sizeof *g->keys);
    if (!g->keys)
        return false;
    for (size_t i = 0; i < c->node_count; i++) {
        if (c->nodes[i].id)
            g->keys[g->key_count++] = (node_key){c->nodes[i].id, i};
        if (c->nodes[i].name)
            g->keys[g->key_count++] = (node_key){c->nodes[i].name, i};
    }
    qsort(g->keys, g->key_count, sizeof *g->keys, compare_keys);
    return true;
}

/* Adds (or only counts, when to is NULL) each node's edges: its nested nodes, its instances. */
static size_t add_edges(const checker *c, const node_graph *g, size_t *fill, size_t *to)
{
    size_t edges = 0;
    for (size_t i = 0; i < c->node_count; i++)
        if (c->nodes[i].parent != NO_NODE) {
            if (to)
                to[fill[c->nodes[i].parent]++] = i;
            else
                fill[c->nodes[i].parent]++;
            edges++;
        }
    for (size_t i = 0; i < c->instance_count; i++) {
        size_t begin, end;
        find_keys(g, c->instances[i].target, &begin, &end);
        for (size_t k = begin; k < end; k++) {
            if (k > begin && g->keys[k].node == g->keys[k - 1].node)
                continue; /* named by id and name alike */
            if (to)
                to[fill[c->instances[i].node]++] = g->keys[k].node;
            else
                fill[c->instances[i].node]++;
            edges++;
        }
    }
    return edges;
}

/*
 * Whether every instance names at most MAX_INSTANCE_TARGETS nodes, so that
 * the graph has at most that many edges per instance; else *line is the
 * first one's.
 */
static bool targets_few(const checker *c, const node_graph *g, long *line)
{
    for (size_t i = 0; i < c->instance_count; i++) {
        size_t begin, end, nodes = 0;
        find_keys(g, c->instances[i].target, &begin, &end);
        for (size_t k = begin; k < end; k++) /* a node named by id and name alike counts once */
            nodes += k == begin || g->keys[k].node != g->keys[k - 1].node;
        if (nodes > MAX_INSTANCE_TARGETS) {
            *line = c->instances[i].line;
            return false;
        }
    }
    return true;
}

/* The graph's edges, its keys made: per node, its nested nodes and those it instances. */
static bool make_edges(const checker *c, node_graph *g)
{
    size_t n = c->node_count;
    size_t *fill = calloc(n + 1, sizeof *fill);
    g->first = calloc(n + 1, sizeof *g->first);
    if (!fill || !g->first) {
        free(fill);
        return false;
    }
    size_t edges = add_edges(c, g, fill, NULL);
    for (size_t i = 0; i < n; i++)
        g->first[i + 1] = g->first[i] + fill[i];
    memcpy(fill, g->first, n * sizeof *fill);
    g->to = malloc((edges + 1) * sizeof *g->to);
    if (g->to)
        add_edges(c, g, fill, g->to);
    free(fill);
    return g->to != NULL;
}

typedef struct {
    unsigned char *state; /* 0 not seen, 1 being expanded, 2 done */
    uint64_t *size;       /* nodes it grows into, capped past MAX_EXPANDED_NODES */
    uint64_t *depth;      /* nodes deep it grows */
    size_t *stack, *edge;
} expansion;

/* What child grows into, added to parent: nodes capped past the limit, depth the deepest. */
static void add_expanded(expansion *x, size_t parent, size_t child)
{
    uint64_t size = x->size[parent] + x->size[child];
    x->size[parent] = size > MAX_EXPANDED_NODES ? MAX_EXPANDED_NODES + 1 : size;
    if (x->depth[child] + 1 > x->depth[parent])
        x->depth[parent] = x->depth[child] + 1;
}

/*
 * Expands node start depth first; false when a node reaches itself again,
 * the nodes of that loop then x->stack[*loop_begin, *loop_end).
 */
static bool expand(const node_graph *g, expansion *x, size_t start, size_t *loop_begin,
                   size_t *loop_end)
{
    size_t top = 0;
    x->stack[top] = start;
    x->edge[top++] = g->first[start];
    x->state[start] = 1;
    x->size[start] = x->depth[start] = 1;
    while (top > 0) {
        size_t node = x->stack[top - 1];
        if (x->edge[top - 1] == g->first[node + 1]) {
            x->state[node] = 2;
            if (--top > 0)
                add_expanded(x, x->stack[top - 1], node);
            continue;
        }
        size_t next = g->to[x->edge[top - 1]++];
        if (x->state[next] == 1) {
            *loop_begin = top - 1;
            while (x->stack[*loop_begin] != next)
                (*loop_begin)--;
            *loop_end = top;
            return false;
        }
        if (x->state[next] == 2) {
            add_expanded(x, node, next);
            continue;
        }
        x->state[next] = 1;
        x->size[next] = x->depth[next] = 1;
        x->stack[top] = next;
        x->edge[top++] = g->first[next];
    }
    return true;
}

/* The line of the first <instance_node> inside node, or 0. */
static long instance_line(const checker *c, size_t node)
{
    for (size_t i = 0; i < c->instance_count; i++)
        if (c->instances[i].node == node)
            return c->instances[i].line;
    return 0;
}

static ur_status expand_all(const checker *c, const node_graph *g, expansion *x)
{
    for (size_t i = 0; i < c->node_count; i++) {
        size_t begin = 0, end = 0;
        if (x->state[i] == 0 && !expand(g, x, i, &begin, &end)) {
            long line = 0; /* every loop passes through an instance */
            for (size_t k = begin; k < end && line == 0; k++)
                line = instance_line(c, x->stack[k]);
            return refuse(c, line, "<instance_node> makes a node contain itself");
        }
        if (x->size[i] > MAX_EXPANDED_NODES || x->depth[i] > MAX_NODE_DEPTH)
            return refuse(c, c->nodes[i].line,
                          "through <instance_node>, this node grows into more than 100000 "
                          "nodes, or more than 1000 deep");
    }
    return UR_OK;
}

/* No node contains itself through instances, and none grows beyond a model's size. */
static ur_status check_nodes(const checker *c)
{
    if (c->instance_count == 0)
        return UR_OK;
    node_graph g = {0};
    size_t n = c->node_count;
    expansion x = {.state = calloc(n, 1),
                   .size = calloc(n, sizeof *x.size),
                   .depth = calloc(n, sizeof *x.depth),
                   .stack = calloc(n, sizeof *x.stack),
                   .edge = calloc(n, sizeof *x.edge)};
    ur_status status = UR_OK;
    long line = 0;
    if (!x.state || !x.size || !x.depth || !x.stack || !x.edge || !make_keys(c, &g))
        status = out_of_memory(c);
    else if (!targets_few(c, &g, &line))
        status = refuse(c, line, "<instance_node> names more than 64 nodes by one id or name");
    else if (!make_edges(c, &g))
        status = out_of_memory(c);
    else
        status = expand_all(c, &g, &x);
    graph_free(&g);
    free(x.state);
    free(x.size);
    free(x.depth);
    free(x.stack);
    free(x.edge);
    return status;
}

/* ---- Reading the document ---------------------------------------------- */

static ur_status open_element(checker *c, int depth)
{
    xmlTextReaderPtr r = c->reader;
    if (c->primitive.open && depth > c->primitive.depth)
        return primitive_child(c); /* assimp reads every element inside a primitive as its own */
    if (c->accessor_depth >= 0 && depth > c->accessor_depth && io_reader_is(r, "param")) {
        count_param(c);
        return UR_OK;
    }
    int kind = primitive_kind(r);
    if (kind >= 0)
        return open_primitive(c, kind, depth);
    if (io_reader_is(r, "float_array"))
        return check_array(c, "float_array", WORDS_REAL);
    if (io_reader_is(r, "Name_array") || io_reader_is(r, "IDREF_array"))
        return check_array(c, (const char *)xmlTextReaderConstLocalName(r), WORDS_ANY);
    if (io_reader_is(r, "accessor"))
        return open_accessor(c, depth);
    if (io_reader_is(r, "node"))
        return open_node(c, depth);
    if (io_reader_is(r, "instance_node"))
        return add_instance(c);
    if (io_reader_is(r, "hex"))
        return refuse(c, current_line(c),
                      "an image given in <hex>: assimp cannot read it; export the model "
                      "without embedding its images");
    return UR_OK;
}

static ur_status close_element(checker *c, int depth)
{
    if (c->accessor_depth == depth)
        c->accessor_depth = -1;
    while (c->open_node_count > 0 && c->open_node_depths[c->open_node_count - 1] >= depth)
        c->open_node_count--;
    if (c->primitive.open && depth == c->primitive.depth)
        return close_primitive(c);
    return UR_OK;
}

static ur_status read_document(checker *c)
{
    int result = 0;
    ur_status status = UR_OK;
    while (status == UR_OK && (result = xmlTextReaderRead(c->reader)) == 1) {
        int type = xmlTextReaderNodeType(c->reader);
        int depth = xmlTextReaderDepth(c->reader);
        if (type == XML_READER_TYPE_ELEMENT) {
            bool empty = xmlTextReaderIsEmptyElement(c->reader) == 1;
            status = open_element(c, depth);
            if (status == UR_OK && empty)
                status = close_element(c, depth);
        } else if (type == XML_READER_TYPE_END_ELEMENT) {
            status = close_element(c, depth);
        }
    }
    if (status == UR_OK && result < 0) /* libxml2's message, when it gave one, replaces this */
        status =
            ur_error_set(c->error, UR_ERROR_INPUT, "%s: Collada: not well-formed XML", c->path);
    if (status == UR_OK)
        status = check_accessors(c);
    if (status == UR_OK)
        status = check_nodes(c);
    return status;
}

static void checker_free(checker *c)
{
    for (size_t i = 0; i < c->array_count; i++)
        free(c->arrays[i].id);
    for (size_t i = 0; i < c->accessor_count; i++)
        free(c->accessors[i].array);
    for (size_t i = 0; i < c->node_count; i++) {
        free(c->nodes[i].id);
        free(c->nodes[i].name);
    }
    for (size_t i = 0; i < c->instance_count; i++)
        free(c->instances[i].target);
    free(c->arrays);
    free(c->accessors);
    free(c->nodes);
    free(c->instances);
}

ur_status io_collada_check(const char *path, const void *data, size_t size, ur_error *error)
{
    if (data && size > INT_MAX) /* libxml2 takes the length as an int */
        return ur_error_set(error, UR_ERROR_INPUT, "%s: %zu bytes: too large to read from memory",
                            path, size);
    /* a float_array beyond libxml2's 10 MB for one text is a large mesh, not an attack */
    int options = XML_PARSE_NONET | XML_PARSE_HUGE | XML_PARSE_BIG_LINES;
    io_xml_capture capture;
    io_xml_capture_begin(&capture);
    errno = 0;
    xmlTextReaderPtr reader = data ? xmlReaderForMemory(data, (int)size, path, NULL, options)
                                   : xmlReaderForFile(path, NULL, options);
    ur_status status = UR_OK;
    if (!reader) {
        status = ur_error_set(error, UR_ERROR_INPUT, "%s: cannot open: %s", path,
                              errno ? strerror(errno) : "not XML");
    } else {
        checker c = {.path = path, .reader = reader, .error = error, .accessor_depth = -1};
        status = read_document(&c);
        checker_free(&c);
        xmlFreeTextReader(reader);
    }
    io_xml_capture_end(&capture);
    if (capture.report.have) /* what went wrong first: the document is not well formed */
        status = io_xml_refuse_file(&capture.report, path, "Collada", error);
    return status;
}
