/*
 * test_context.c: the run's context (unroll/base.h): its cancel flag, its
 * output set, its messages and its write-failure hook, each kept to the
 * context it belongs to, and new files getting the mode the umask gives.
 */
#include "test_support.h"

#include "unroll/base.h"
#include "unroll/io.h"

static char directory[128];

static int make_directory(void **state)
{
    (void)state;
    snprintf(directory, sizeof directory, "/tmp/unroll-test-context-XXXXXX");
    return mkdtemp(directory) ? 0 : -1;
}

static int remove_directory(void **state)
{
    (void)state;
    return remove_test_directory(directory);
}

static const ur_vec3 square[4] = {{0, 0, 0}, {10, 0, 0}, {10, 10, 0}, {0, 10, 0}};

/* Writes the square as a curve to directory/name in context; returns the status. */
static ur_status write_curve(ur_context *context, const char *name, char *path, size_t size,
                             ur_error *error)
{
    path_in(directory, name, path, size);
    return ur_curve_csv_write(path, square, 4, context, error);
}

static void test_cancel_flag(void **state)
{
    (void)state;
    ur_context *context = ur_context_new();
    assert_non_null(context);
    ur_error error = {0};
    assert_false(ur_context_cancelled(context));
    assert_int_equal(ur_context_check(context, &error), UR_OK);
    ur_context_cancel(context);
    assert_true(ur_context_cancelled(context));
    assert_int_equal(ur_context_check(context, &error), UR_ERROR_CANCELLED);
    assert_string_equal(error.message, "cancelled");
    ur_context_cancel_clear(context);
    assert_int_equal(ur_context_check(context, &error), UR_OK);
    /* No context: never cancelled, and cancelling it does nothing. */
    ur_context_cancel(NULL);
    assert_false(ur_context_cancelled(NULL));
    assert_int_equal(ur_context_check(NULL, &error), UR_OK);
    ur_context_free(context);
}

static void test_output_set_holds_files_until_its_end(void **state)
{
    (void)state;
    ur_context *context = ur_context_new();
    ur_error error = {0};
    char first[256], second[256];
    ur_output_set_begin(context);
    assert_int_equal(write_curve(context, "first.csv", first, sizeof first, &error), UR_OK);
    ur_output_set_begin(context); /* sets nest: only the outermost end renames */
    assert_int_equal(write_curve(context, "second.csv", second, sizeof second, &error), UR_OK);
    assert_int_equal(ur_output_set_end(context, true, &error), UR_OK);
    assert_false(exists(first));
    assert_false(exists(second));
    assert_int_equal(entries_in(directory), 2); /* the two hidden temporaries */
    assert_int_equal(ur_output_set_end(context, true, &error), UR_OK);
    assert_true(exists(first));
    assert_true(exists(second));
    assert_int_equal(entries_in(directory), 2);
    unlink(first);
    unlink(second);
    ur_context_free(context);
}

static void test_refused_set_leaves_disk_as_it_was(void **state)
{
    (void)state;
    ur_context *context = ur_context_new();
    ur_error error = {0};
    char path[256];
    path_in(directory, "kept.csv", path, sizeof path);
    FILE *old = fopen(path, "w");
    assert_non_null(old);
    fputs("old\n", old);
    fclose(old);
    ur_output_set_begin(context);
    assert_int_equal(write_curve(context, "kept.csv", path, sizeof path, &error), UR_OK);
    assert_int_equal(ur_output_set_end(context, false, &error), UR_OK);
    char line[16] = "";
    FILE *file = fopen(path, "r");
    assert_non_null(file);
    assert_non_null(fgets(line, sizeof line, file));
    fclose(file);
    assert_string_equal(line, "old\n");
    assert_int_equal(entries_in(directory), 1); /* the temporary is gone */
    unlink(path);
    ur_context_free(context);
}

static void test_cancelled_set_renames_nothing(void **state)
{
    (void)state;
    ur_context *context = ur_context_new();
    ur_error error = {0};
    char path[256];
    ur_output_set_begin(context);
    assert_int_equal(write_curve(context, "cancelled.csv", path, sizeof path, &error), UR_OK);
    ur_context_cancel(context);
    assert_int_equal(ur_output_set_end(context, true, &error), UR_ERROR_CANCELLED);
    assert_false(exists(path));
    assert_int_equal(entries_in(directory), 0);
    /* A file written alone in a cancelled context is not renamed either. */
    assert_int_equal(write_curve(context, "alone.csv", path, sizeof path, &error),
                     UR_ERROR_CANCELLED);
    assert_int_equal(entries_in(directory), 0);
    ur_context_free(context);
}

static void test_contexts_are_independent(void **state)
{
    (void)state;
    ur_context *holding = ur_context_new(), *other = ur_context_new();
    ur_error error = {0};
    char held[256], failed[256], free_file[256], unbound[256];
    ur_output_set_begin(holding);
    assert_int_equal(write_curve(holding, "held.csv", held, sizeof held, &error), UR_OK);
    ur_context_cancel(holding);
    ur_context_fail_writes_after(holding, 0);
    assert_int_equal(write_curve(other, "other.csv", free_file, sizeof free_file, &error), UR_OK);
    assert_int_equal(write_curve(NULL, "none.csv", unbound, sizeof unbound, &error), UR_OK);
    assert_true(exists(free_file)); /* renamed at once: not in the other context's set */
    assert_true(exists(unbound));
    assert_int_not_equal(write_curve(holding, "failed.csv", failed, sizeof failed, &error), UR_OK);
    assert_false(exists(held));
    assert_int_equal(entries_in(directory), 3); /* held's temporary and the two files */
    /* Freeing a context with a set still open removes what it holds. */
    ur_context_free(holding);
    assert_false(exists(held));
    assert_int_equal(entries_in(directory), 2);
    unlink(free_file);
    unlink(unbound);
    ur_context_free(other);
}

static void test_write_budget_fails_like_a_full_disk(void **state)
{
    (void)state;
    ur_context *context = ur_context_new();
    ur_error error = {0};
    char path[256];
    ur_context_fail_writes_after(context, 10);
    assert_int_equal(write_curve(context, "full.csv", path, sizeof path, &error), UR_ERROR_IO);
    assert_non_null(strstr(error.message, path));
    assert_false(exists(path));
    assert_int_equal(entries_in(directory), 0);
    /* The budget is spent for this context only; lifting it lets writes through again. */
    ur_context_fail_writes_after(context, -1);
    assert_int_equal(write_curve(context, "full.csv", path, sizeof path, &error), UR_OK);
    unlink(path);
    ur_context_free(context);
}

static ur_message_kind seen_kind;
static char seen_message[64], seen_setting[64];

static void remember(void *data, ur_message_kind kind, const char *message, const char *setting)
{
    *(int *)data += 1;
    seen_kind = kind;
    snprintf(seen_message, sizeof seen_message, "%s", message);
    snprintf(seen_setting, sizeof seen_setting, "%s", setting);
}

static void test_messages_go_to_the_handler(void **state)
{
    (void)state;
    ur_context *context = ur_context_new();
    int calls = 0;
    ur_context_message(context, UR_MESSAGE_WARNING, "dropped"); /* no handler yet */
    ur_context_set_message_handler(context, remember, &calls);
    ur_context_message(context, UR_MESSAGE_WARNING, "seam %s has no tab", "A3");
    assert_int_equal(calls, 1);
    assert_int_equal(seen_kind, UR_MESSAGE_WARNING);
    assert_string_equal(seen_message, "seam A3 has no tab");
    assert_string_equal(seen_setting, "");
    ur_context_message_about(context, UR_MESSAGE_NOTE, "no-split", "cut into %d", 2);
    assert_int_equal(calls, 2);
    assert_int_equal(seen_kind, UR_MESSAGE_NOTE);
    assert_string_equal(seen_message, "cut into 2");
    assert_string_equal(seen_setting, "no-split");
    ur_context_message(NULL, UR_MESSAGE_NOTE, "nobody hears this");
    assert_int_equal(calls, 2);
    ur_context_free(context);
}

/* The mode of a file written with umask mask, as stat reports its permission bits. */
static mode_t mode_under(mode_t mask)
{
    mode_t old = umask(mask);
    ur_error error = {0};
    char path[256];
    ur_status status = write_curve(NULL, "mode.csv", path, sizeof path, &error);
    umask(old);
    assert_int_equal(status, UR_OK);
    struct stat info;
    assert_int_equal(stat(path, &info), 0);
    unlink(path);
    return info.st_mode & 0777;
}

static void test_new_files_follow_the_umask(void **state)
{
    (void)state;
    assert_int_equal(mode_under(022), 0644);
    assert_int_equal(mode_under(077), 0600);
    assert_int_equal(mode_under(002), 0664);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_cancel_flag),
        cmocka_unit_test(test_output_set_holds_files_until_its_end),
        cmocka_unit_test(test_refused_set_leaves_disk_as_it_was),
        cmocka_unit_test(test_cancelled_set_renames_nothing),
        cmocka_unit_test(test_contexts_are_independent),
        cmocka_unit_test(test_write_budget_fails_like_a_full_disk),
        cmocka_unit_test(test_messages_go_to_the_handler),
        cmocka_unit_test(test_new_files_follow_the_umask),
    };
    return cmocka_run_group_tests(tests, make_directory, remove_directory);
}
