/*
 * mesh_gltf.c: a glTF document checked before assimp reads it.
 *
 * assimp 5.2 has two readers for .gltf and .glb, and asks each whether a
 * file is its own: glTF 2.0's parses the JSON (rapidjson, default rules)
 * and reads its "asset".  When neither takes the file, assimp tries every
 * other reader it has on the bytes, and some of those crash on what they
 * find: a broken .gltf holding a zip archive went to its 3MF reader,
 * which stops the process (an ai_assert; found by fuzz_mesh), a PLY header
 * made its PLY reader loop for ever.  So a glTF file is taken only where
 * glTF 2.0's reader will take it: JSON as rapidjson reads it, or stricter
 * (no byte-order mark, no number of 1e300 or more, nothing nested more
 * than 256 deep, a \u escape of half a surrogate pair only as the first of
 * a whole pair), its root an object whose first "asset" is an object with
 * a first "version" that is a string starting with 2, and a first
 * "profile", if any, that is an object; a .glb with glTF 2.0's header, its
 * JSON chunk all there, and a BIN chunk where the header's length says one
 * follows.  glTF 1.0, which assimp reads with its other reader, is
 * refused: it has been superseded since 2017.  The first bytes are
 * looked at before the rest is read: a file that does not start as glTF
 * is refused without reading it whole.
 */
#include "io_internal.h"

#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Deeper than this is no glTF; rapidjson reads nesting by recursion. */
#define MOST_DEPTH 256
/* A number of 10 to this power or more is refused (rapidjson refuses what a double cannot hold). */
#define MOST_MAGNITUDE 300

/* What the document says of itself, and where reading stopped on an error. */
typedef struct json_reader {
    const unsigned char *start, *at, *end;
    const char *problem; /* NULL while the JSON is well formed */
    bool asset_seen, version_ok;
    char version[16]; /* the start of asset.version, for the message */
} json_reader;

static bool fail(json_reader *r, const char *problem)
{
    if (!r->problem)
        r->problem = problem;
    return false;
}

static void skip_blanks(json_reader *r)
{
    while (r->at < r->end && (*r->at == ' ' || *r->at == '\t' || *r->at == '\n' || *r->at == '\r'))
        r->at++;
}

static bool take(json_reader *r, char c)
{
    if (r->at < r->end && *r->at == (unsigned char)c) {
        r->at++;
        return true;
    }
    return false;
}

static bool is_digit(const json_reader *r)
{
    return r->at < r->end && *r->at >= '0' && *r->at <= '9';
}

/* Four hexadecimal digits after \u, into *code. */
static bool read_hex4(json_reader *r, unsigned *code)
{
    *code = 0;
    for (int i = 0; i < 4; i++, r->at++) {
        if (r->at >= r->end)
            return fail(r, "a \\u escape was cut short");
        unsigned c = *r->at, digit = c >= '0' && c <= '9'   ? c - '0'
                                     : c >= 'a' && c <= 'f' ? c - 'a' + 10
                                     : c >= 'A' && c <= 'F' ? c - 'A' + 10
                                                            : 16;
        if (digit > 15)
            return fail(r, "a \\u escape needs four hexadecimal digits");
        *code = 16 * *code + digit;
    }
    return true;
}

/* Appends code point code to a name being decoded (what does not fit is dropped). */
static void add_code(char *name, size_t size, size_t *length, unsigned code)
{
    unsigned char bytes[4];
    size_t count = code < 0x80 ? 1 : code < 0x800 ? 2 : code < 0x10000 ? 3 : 4;
    if (count == 1)
        bytes[0] = (unsigned char)code;
    else {
        for (size_t i = count - 1; i > 0; i--, code >>= 6)
            bytes[i] = (unsigned char)(0x80 | (code & 0x3F));
        bytes[0] = (unsigned char)((count == 2 ? 0xC0 : count == 3 ? 0xE0 : 0xF0) | code);
    }
    for (size_t i = 0; i < count; i++, (*length)++)
        if (*length < size)
            name[*length] = (char)bytes[i];
}

/* The escape after a backslash, its code point added to the name. */
static bool read_escape(json_reader *r, char *name, size_t size, size_t *length)
{
    static const char plain[] = "\"\\/bfnrt", meant[] = "\"\\/\b\f\n\r\t";
    if (r->at >= r->end)
        return fail(r, "a string was not closed");
    const char *simple = *r->at ? strchr(plain, *r->at) : NULL;
    if (simple) {
        r->at++;
        add_code(name, size, length, (unsigned char)meant[simple - plain]);
        return true;
    }
    if (!take(r, 'u'))
        return fail(r, "a backslash before a letter that is no escape");
    unsigned code;
    if (!read_hex4(r, &code))
        return false;
    if (code >= 0xDC00 && code <= 0xDFFF)
        return fail(r, "a \\u escape of the second half of a surrogate pair alone");
    if (code >= 0xD800 && code <= 0xDBFF) {
        unsigned low;
        if (!take(r, '\\') || !take(r, 'u') || !read_hex4(r, &low) || low < 0xDC00 || low > 0xDFFF)
            return fail(r, "a \\u escape of half a surrogate pair without its other half");
        code = 0x10000 + ((code - 0xD800) << 10) + (low - 0xDC00);
    }
    add_code(name, size, length, code);
    return true;
}

/* A string (at its opening quote), decoded into name (its first size bytes) and *length. */
static bool read_string(json_reader *r, char *name, size_t size, size_t *length)
{
    *length = 0;
    r->at++; /* the quote */
    for (;;) {
        if (r->at >= r->end)
            return fail(r, "a string was not closed");
        unsigned char c = *r->at++;
        if (c == '"')
            return true;
        if (c < 0x20)
            return fail(r, "a control character inside a string");
        if (c == '\\') {
            if (!read_escape(r, name, size, length))
                return false;
        } else {
            if (*length < size)
                name[*length] = (char)c;
            (*length)++;
        }
    }
}

/* The digits of an exponent, as a number no larger than 10^9. */
static bool read_exponent(json_reader *r, long *exponent)
{
    bool negative = take(r, '-');
    if (!negative)
        take(r, '+');
    if (!is_digit(r))
        return fail(r, "a number's exponent has no digits");
    *exponent = 0;
    for (int digits = 0; is_digit(r); digits++, r->at++) {
        if (digits == 9)
            return fail(r, "a number's exponent has more than nine digits");
        *exponent = 10 * *exponent + (*r->at - '0');
    }
    if (negative)
        *exponent = -*exponent;
    return true;
}

static bool read_number(json_reader *r)
{
    take(r, '-');
    long whole_digits = 0;
    if (take(r, '0'))
        whole_digits = 1;
    else if (is_digit(r))
        for (; is_digit(r); r->at++)
            whole_digits++;
    else
        return fail(r, "a minus sign without a number");
    if (take(r, '.')) {
        if (!is_digit(r))
            return fail(r, "a number's point has no digits after it");
        while (is_digit(r))
            r->at++;
    }
    long exponent = 0;
    if ((take(r, 'e') || take(r, 'E')) && !read_exponent(r, &exponent))
        return false;
    if (whole_digits - 1 + exponent >= MOST_MAGNITUDE)
        return fail(r, "a number of 1e300 or more");
    return true;
}

static bool read_word(json_reader *r, const char *word)
{
    size_t length = strlen(word);
    if ((size_t)(r->end - r->at) < length || memcmp(r->at, word, length) != 0)
        return fail(r, "a value was expected");
    r->at += length;
    return true;
}

/* How an object's members are looked at: the root's first "asset", the asset's first "version". */
typedef enum { PLAIN, ROOT, ASSET } object_role;

static bool read_value(json_reader *r, int depth);
static bool read_object(json_reader *r, int depth, object_role role);

/*
 * A member's value (at it), the member named name: the root's first
 * "asset", and that asset's first "version" and "profile", are checked as
 * glTF 2.0's reader reads them when it decides whether the file is its own.
 */
static bool read_member(json_reader *r, int depth, object_role role, const char *name,
                        size_t length, bool seen[2])
{
    bool version = length == 7 && memcmp(name, "version", 7) == 0;
    bool profile = length == 7 && memcmp(name, "profile", 7) == 0;
    if (role == ROOT && length == 5 && memcmp(name, "asset", 5) == 0 && !seen[0]) {
        seen[0] = true;
        if (r->at >= r->end || *r->at != '{')
            return fail(r, "its \"asset\" is not an object");
        r->asset_seen = true;
        return read_object(r, depth + 1, ASSET);
    }
    if (role == ASSET && version && !seen[0]) {
        seen[0] = true;
        if (r->at >= r->end || *r->at != '"')
            return fail(r, "its asset's \"version\" is not a string");
        size_t got;
        if (!read_string(r, r->version, sizeof r->version - 1, &got))
            return false;
        r->version[got < sizeof r->version - 1 ? got : sizeof r->version - 1] = '\0';
        r->version_ok = got > 0 && r->version[0] == '2';
        return true;
    }
    if (role == ASSET && profile && !seen[1]) {
        seen[1] = true;
        if (r->at >= r->end || *r->at != '{')
            return fail(r, "its asset's \"profile\" is not an object");
    }
    return read_value(r, depth);
}

/* An object (at its brace) at depth, its members looked at as its role says. */
static bool read_object(json_reader *r, int depth, object_role role)
{
    r->at++;
    skip_blanks(r);
    if (take(r, '}'))
        return true;
    bool seen[2] = {false, false};
    for (;;) {
        if (r->at >= r->end || *r->at != '"')
            return fail(r, "a member's name was expected");
        char name[16];
        size_t length;
        if (!read_string(r, name, sizeof name, &length))
            return false;
        skip_blanks(r);
        if (!take(r, ':'))
            return fail(r, "a ':' was expected after a member's name");
        skip_blanks(r);
        if (!read_member(r, depth, role, name, length, seen))
            return false;
        skip_blanks(r);
        if (take(r, '}'))
            return true;
        if (!take(r, ','))
            return fail(r, "a ',' or '}' was expected");
        skip_blanks(r);
    }
}

static bool read_array(json_reader *r, int depth)
{
    r->at++;
    skip_blanks(r);
    if (take(r, ']'))
        return true;
    for (;;) {
        if (!read_value(r, depth))
            return false;
        skip_blanks(r);
        if (take(r, ']'))
            return true;
        if (!take(r, ','))
            return fail(r, "a ',' or ']' was expected");
        skip_blanks(r);
    }
}

/* A value inside an object or array at depth (the root object's is 1). */
static bool read_value(json_reader *r, int depth)
{
    if (r->at >= r->end)
        return fail(r, "a value was expected");
    unsigned char c = *r->at;
    if ((c == '{' || c == '[') && depth >= MOST_DEPTH)
        return fail(r, "objects and arrays nested more than 256 deep");
    char none[1];
    size_t length;
    if (c == '{')
        return read_object(r, depth + 1, PLAIN);
    if (c == '[')
        return read_array(r, depth + 1);
    if (c == '"')
        return read_string(r, none, 0, &length);
    if (c == 't')
        return read_word(r, "true");
    if (c == 'f')
        return read_word(r, "false");
    if (c == 'n')
        return read_word(r, "null");
    if (c == '-' || (c >= '0' && c <= '9'))
        return read_number(r);
    return fail(r, "a value was expected");
}

/* The line of the reader's place, counted from 1. */
static size_t line_at(const json_reader *r)
{
    size_t line = 1;
    for (const unsigned char *p = r->start; p < r->at; p++)
        line += *p == '\n';
    return line;
}

/*
 * The JSON of a glTF 2.0 document in the length bytes at text, as
 * rapidjson reads them in place: up to the first NUL; of the file at path,
 * or of its JSON chunk (a .glb).
 */
static ur_status check_json(const char *path, bool chunk, const unsigned char *text, size_t length,
                            ur_error *error)
{
    const char *where = chunk ? ": JSON chunk" : "";
    const unsigned char *nul = memchr(text, 0, length);
    json_reader r = {.start = text, .at = text, .end = nul ? nul : text + length};
    skip_blanks(&r);
    if (r.end - r.at >= 3 && memcmp(r.at, "\xEF\xBB\xBF", 3) == 0)
        fail(&r, "it starts with a byte-order mark, which assimp's glTF reader does not take");
    else if (r.at >= r.end || *r.at != '{')
        fail(&r, "it is not a JSON object (glTF is one)");
    else if (read_object(&r, 1, ROOT)) {
        skip_blanks(&r);
        if (r.at < r.end)
            fail(&r, "something follows the JSON object");
    }
    if (r.problem)
        return ur_error_set(error, UR_ERROR_INPUT, "%s%s:%zu: not a glTF file assimp reads: %s",
                            path, where, line_at(&r), r.problem);
    if (!r.asset_seen || r.version[0] == '\0')
        return ur_error_set(error, UR_ERROR_INPUT,
                            "%s%s: not a glTF file assimp reads: no \"asset\" with a \"version\"",
                            path, where);
    if (!r.version_ok)
        return ur_error_set(error, UR_ERROR_INPUT,
                            "%s%s: glTF version '%s': only glTF 2.0 is read (export glTF 2.0)",
                            path, where, r.version);
    return UR_OK;
}

/* A little-endian 32-bit word. */
static uint32_t word_at(const unsigned char *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

enum { GLB_HEADER = 12, GLB_CHUNK = 8 };
#define CHUNK_JSON UINT32_C(0x4E4F534A)
#define CHUNK_BIN UINT32_C(0x004E4942)

/* A binary glTF: glTF 2.0's header, its JSON chunk whole and checked, a BIN chunk if said. */
static ur_status check_glb(const char *path, const unsigned char *data, size_t size,
                           ur_error *error)
{
    if (size < GLB_HEADER + GLB_CHUNK || memcmp(data, "glTF", 4) != 0)
        return ur_error_set(error, UR_ERROR_INPUT,
                            "%s: not a binary glTF file: no header and JSON chunk", path);
    if (word_at(data + 4) != 2)
        return ur_error_set(error, UR_ERROR_INPUT,
                            "%s: binary glTF version %lu: only glTF 2.0 is read", path,
                            (unsigned long)word_at(data + 4));
    uint64_t json_length = word_at(data + GLB_HEADER);
    if (word_at(data + GLB_HEADER + 4) != CHUNK_JSON)
        return ur_error_set(error, UR_ERROR_INPUT,
                            "%s: binary glTF: its first chunk is not its JSON", path);
    if (json_length > size - GLB_HEADER - GLB_CHUNK)
        return ur_error_set(error, UR_ERROR_INPUT,
                            "%s: binary glTF: its JSON chunk of %llu bytes goes past the end", path,
                            (unsigned long long)json_length);
    uint64_t padding = ((json_length + 3) & ~UINT64_C(3)) - json_length;
    uint64_t bin_at = GLB_HEADER + GLB_CHUNK + json_length + padding;
    /* assimp reads a BIN chunk when the header's length reaches past its header */
    if (word_at(data + 8) >= bin_at + GLB_CHUNK &&
        (bin_at + GLB_CHUNK > size || word_at(data + bin_at + 4) != CHUNK_BIN))
        return ur_error_set(error, UR_ERROR_INPUT,
                            "%s: binary glTF: its length says a BIN chunk follows its JSON, and "
                            "none does",
                            path);
    return check_json(path, true, data + GLB_HEADER + GLB_CHUNK, (size_t)json_length, error);
}

enum { START_BYTES = 64 };

/* The first bytes of the file at path, or of data; how many there are. */
static ur_status read_start(const char *path, const void *data, size_t size,
                            unsigned char start[START_BYTES], size_t *count, ur_error *error)
{
    if (data) {
        *count = size < START_BYTES ? size : START_BYTES;
        memcpy(start, data, *count);
        return UR_OK;
    }
    FILE *file = fopen(path, "rb");
    if (!file)
        return ur_error_set(error, UR_ERROR_INPUT, "%s: cannot open: %s", path, strerror(errno));
    *count = fread(start, 1, START_BYTES, file);
    bool failed = ferror(file) != 0;
    if (fclose(file) != 0 || failed)
        return ur_error_set(error, UR_ERROR_INPUT, "%s: cannot read: %s", path, strerror(errno));
    return UR_OK;
}

/*
 * Whether the start is a glTF's: "glTF" for a .glb; for a .gltf a JSON
 * object, after blanks or a byte-order mark (refused later, with its own
 * message).  Looked at before the whole file is read, so that a large
 * file that is no glTF is refused at once.
 */
static ur_status check_start(const char *path, const void *data, size_t size, ur_error *error)
{
    unsigned char start[START_BYTES] = {0};
    size_t count = 0;
    ur_status status = read_start(path, data, size, start, &count, error);
    if (status != UR_OK)
        return status;
    if (io_has_extension(path, "glb")) {
        if (count < 4 || memcmp(start, "glTF", 4) != 0)
            return ur_error_set(error, UR_ERROR_INPUT,
                                "%s: not a binary glTF file: it does not start with 'glTF'", path);
        return UR_OK;
    }
    size_t i = count >= 3 && memcmp(start, "\xEF\xBB\xBF", 3) == 0 ? 3 : 0;
    while (i < count && start[i] != '\0' && strchr(" \t\r\n", start[i]))
        i++;
    if (i >= count || start[i] != '{')
        return ur_error_set(error, UR_ERROR_INPUT,
                            "%s: not a glTF file: it does not start with '{' (glTF is JSON)", path);
    return UR_OK;
}

ur_status io_gltf_check(const char *path, const void *data, size_t size, ur_error *error)
{
    ur_status status = check_start(path, data, size, error);
    if (status != UR_OK)
        return status;
    /* size: the file's, or the data's; assimp's glTF reader refuses 4 GB of JSON */
    if (size >= UINT32_MAX)
        return ur_error_set(error, UR_ERROR_INPUT, "%s: %zu bytes: too large for a glTF file", path,
                            size);
    char *read = NULL;
    if (!data) {
        status = io_read_file(path, 0, "", &read, &size, error);
        if (status != UR_OK)
            return status;
        data = read;
    }
    status = io_has_extension(path, "glb") ? check_glb(path, data, size, error)
                                           : check_json(path, false, data, size, error);
    free(read);
    return status;
}
