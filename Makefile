# unroll: build, test, demo, bench and install.
#
#   make            build libunroll.a, libunroll.so and the unroll command
#   make demo       install what is missing, build, unroll the samples into out/
#   make check      install what is missing, build, run every test
#   make check SANITIZE=1   the same with AddressSanitizer and UBSan
#   make check VALGRIND=1   the same with the CLI tests' runs of unroll under
#                           valgrind memcheck (no errors, no leaks)
#   make bench      benchmarks (never part of make check)
#   make fuzz       libFuzzer targets (clang, ASan, UBSan), each run FUZZ_SECONDS
#   make install    PREFIX=/usr/local DESTDIR=: the command, man pages and
#                   profiles, the libraries, headers and unroll.pc

PREFIX ?= /usr/local
DESTDIR ?=
BINDIR = $(PREFIX)/bin
LIBDIR = $(PREFIX)/lib
INCLUDEDIR = $(PREFIX)/include
PKGCONFIGDIR = $(LIBDIR)/pkgconfig
MANDIR = $(PREFIX)/share/man
PROFILEDIR = $(PREFIX)/share/unroll/profiles

# The library's version is UR_VERSION; its soname changes with the major number.
VERSION := $(shell sed -n 's/^\#define UR_VERSION "\(.*\)"/\1/p' include/unroll/base.h)
SONAME = libunroll.so.$(firstword $(subst ., ,$(VERSION)))

CC ?= cc
PKG_CONFIG ?= pkg-config
PACKAGES = libxml-2.0 gsl jansson geos cairo assimp minizip
TEST_PACKAGES = cmocka

# FUZZ=1 is how `make fuzz` builds the library and its targets: clang with
# libFuzzer's coverage instrumentation, ASan and UBSan, in a tree of its own.
ifeq ($(FUZZ),1)
BUILD = build/fuzz
FUZZ_CC ?= clang
override CC = $(FUZZ_CC)
SANITIZE_FLAGS = -fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=all \
	-fno-omit-frame-pointer
OPTIMISE = -O1 -g
else ifeq ($(SANITIZE),1)
BUILD = build/sanitize
SANITIZE_FLAGS = -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer
OPTIMISE = -O1 -g
else
BUILD = build/release
SANITIZE_FLAGS =
OPTIMISE = -O2 -g
endif

# Recursive (=) so that pkg-config is asked only once install-deps has run.
CFLAGS_ALL = -std=c11 -D_XOPEN_SOURCE=700 -Wall -Wextra -Wpedantic -Werror \
	-Wshadow -Wstrict-prototypes $(OPTIMISE) $(SANITIZE_FLAGS) -Iinclude \
	$(shell $(PKG_CONFIG) --cflags $(PACKAGES)) \
	-I/usr/include/suitesparse $(CFLAGS)
LDLIBS_ALL = $(shell $(PKG_CONFIG) --libs $(PACKAGES)) -lcholmod -lhersheyfont -lhpdf -lm $(LDLIBS)
LDFLAGS_ALL = $(SANITIZE_FLAGS) $(LDFLAGS)

LIB_SOURCES = $(wildcard src/base/*.c src/geom/*.c src/core/*.c src/surface/*.c src/develop/*.c \
	src/analyze/*.c src/mesh/*.c src/flatten/*.c src/allow/*.c src/nest/*.c src/io/*.c src/out/*.c \
	src/job/*.c)
CLI_SOURCES = $(wildcard src/cli/*.c)
UNIT_SOURCES = $(wildcard tests/unit/test_*.c)
BENCH_SOURCES = $(wildcard bench/*.c)
# One fuzz target per input path: tests/fuzz/fuzz_NAME.c, seeds in tests/fuzz/corpus/NAME/.
FUZZ_SOURCES = $(wildcard tests/fuzz/fuzz_*.c)
FUZZ_HEADERS = $(wildcard tests/fuzz/*.h)
FUZZ_SECONDS ?= 10

LIB_OBJECTS = $(LIB_SOURCES:%.c=$(BUILD)/%.o)
CLI_OBJECTS = $(CLI_SOURCES:%.c=$(BUILD)/%.o)
UNIT_BINARIES = $(UNIT_SOURCES:tests/unit/%.c=$(BUILD)/tests/%)
BENCH_BINARIES = $(BENCH_SOURCES:bench/%.c=$(BUILD)/bench/%)
FUZZ_BINARIES = $(FUZZ_SOURCES:tests/fuzz/%.c=$(BUILD)/fuzz/%)
# The same targets without libFuzzer, replaying the seeds and regressions in make check.
REPLAY_BINARIES = $(FUZZ_SOURCES:tests/fuzz/%.c=$(BUILD)/replay/%)

# VALGRIND=1: tests/run-tests runs the CLI tests with tests/valgrind-unroll
# in place of the command (the release build under valgrind memcheck, full
# leak check, suppressions in tests/valgrind.supp); any error or leak fails.
# valgrind's memory manager is not ASan's, hence not with SANITIZE=1.  These
# CLI tests are skipped under valgrind only:
#   a_mesh_too_large_for_memory_fails_cleanly: its ulimit -v limits valgrind,
#     which reserves address space of its own, and not unroll's estimate
#     (the sanitizer build skips it for the same reason);
#   nest_search_is_repeatable: its search has a budget of wall-clock time
#     that it must not reach; 20 to 50 times slower under valgrind it can,
#     and then where it stops depends on the machine's load;
#   signals_stop_cleanly: it signals unroll 0.3 s and 1 s after starting it,
#     which under valgrind can be before unroll has set its handlers up;
#   papercraft_of_the_sample_meshes: its five unfoldings with tabs take 9 s,
#     well over half an hour under valgrind (one UV sphere alone ran 9
#     minutes).  The same code runs under valgrind in the assembly guide's
#     and the seams' tests;
#   adjust_reshapes_a_wavy_rail: its least-squares repairs of rail 2 (as
#     written and to 3 decimals) take 20 s, 10 to 20 minutes under
#     valgrind; the sanitizer build runs it, and test_rail_repair the same
#     repair, and adjust_rail2_repairs_a_short_rail
#     runs the repair's code under valgrind; adjust_irons_out_a_bump_and_a_dent
#     likewise (5 s; test_rail_repair repairs the same rails).
VALGRIND_SKIP = a_mesh_too_large_for_memory_fails_cleanly nest_search_is_repeatable \
	signals_stop_cleanly papercraft_of_the_sample_meshes adjust_reshapes_a_wavy_rail \
	adjust_irons_out_a_bump_and_a_dent
ifeq ($(VALGRIND)$(SANITIZE),11)
$(error VALGRIND=1 and SANITIZE=1 do not mix: valgrind cannot run ASan's build)
endif

# libunroll.a, installed: one relocatable object of every library object
# with the hidden (not UR_API) symbols made local, so that it defines no
# name outside the public API.  The tests, benches and fuzz targets, which
# also call internal functions, link the objects themselves (OBJECT_ARCHIVE).
LIBRARY = $(BUILD)/libunroll.a
LIBRARY_OBJECT = $(BUILD)/libunroll.o
OBJECT_ARCHIVE = $(BUILD)/libunroll-objects.a
# libunroll.so.VERSION, with the links SONAME (what programs load) and
# libunroll.so (what -lunroll finds).
SHARED_FILE = $(BUILD)/libunroll.so.$(VERSION)
SHARED = $(BUILD)/libunroll.so
PROGRAM = $(BUILD)/unroll
# make check installs here and builds examples/ against the installed copy.
INSTALL_CHECK_PREFIX = $(CURDIR)/$(BUILD)/install-check

.PHONY: all demo readme check test deps bench fuzz fuzz-targets install clean format

all: $(PROGRAM) $(SHARED)

# The library's objects go into the shared library too: position-independent,
# and every symbol hidden that the headers do not mark UR_API.
$(LIB_OBJECTS): PIC = -fPIC -fvisibility=hidden

$(BUILD)/%.o: %.c
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_ALL) $(PIC) -MMD -MP -c $< -o $@

$(OBJECT_ARCHIVE): $(LIB_OBJECTS)
	@mkdir -p $(dir $@)
	rm -f $@
	ar rcs $@ $^

$(LIBRARY_OBJECT): $(LIB_OBJECTS)
	$(LD) -r -o $@.whole $^
	objcopy --localize-hidden $@.whole $@
	rm -f $@.whole

$(LIBRARY): $(LIBRARY_OBJECT)
	rm -f $@
	ar rcs $@ $^

$(SHARED_FILE): $(LIB_OBJECTS)
	$(CC) -shared -Wl,-soname,$(SONAME) $(LDFLAGS_ALL) -o $@ $^ $(LDLIBS_ALL)

$(SHARED): $(SHARED_FILE)
	ln -sf $(notdir $(SHARED_FILE)) $(BUILD)/$(SONAME)
	ln -sf $(SONAME) $@

$(BUILD)/unroll.pc: unroll.pc.in include/unroll/base.h
	sed -e 's|@PREFIX@|$(PREFIX)|' -e 's|@LIBDIR@|$(LIBDIR)|' -e 's|@INCLUDEDIR@|$(INCLUDEDIR)|' \
		-e 's|@PROFILEDIR@|$(PROFILEDIR)|' -e 's|@VERSION@|$(VERSION)|' unroll.pc.in >$@

$(PROGRAM): $(CLI_OBJECTS) $(LIBRARY)
	$(CC) $(LDFLAGS_ALL) -o $@ $(CLI_OBJECTS) $(LIBRARY) $(LDLIBS_ALL)

# test_support.h and nest_sets.h are shared, header-only: a change to them rebuilds every
# test (and nest_sets.h, the benches that make the same sets of parts).
$(BUILD)/tests/%: tests/unit/%.c tests/unit/test_support.h tests/unit/test_geos.h tests/unit/nest_sets.h $(OBJECT_ARCHIVE)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_ALL) $(shell $(PKG_CONFIG) --cflags $(TEST_PACKAGES)) -o $@ $< \
		$(OBJECT_ARCHIVE) $(LDFLAGS_ALL) $(TEST_LDFLAGS) $(LDLIBS_ALL) \
		$(shell $(PKG_CONFIG) --libs $(TEST_PACKAGES))

# The library's own calls to the allocator (its objects' and the test's,
# not those of GEOS, cairo or the C library) go through the test's
# __wrap_ functions, which refuse one of them at a time.
$(BUILD)/tests/test_out_of_memory: TEST_LDFLAGS = \
	-Wl,--wrap=malloc,--wrap=calloc,--wrap=realloc,--wrap=strdup

$(BUILD)/bench/%: bench/%.c tests/unit/nest_sets.h $(OBJECT_ARCHIVE)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_ALL) -o $@ $< $(OBJECT_ARCHIVE) $(LDFLAGS_ALL) $(LDLIBS_ALL)

$(BUILD)/fuzz/%: tests/fuzz/%.c $(FUZZ_HEADERS) $(OBJECT_ARCHIVE)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_ALL) -fsanitize=fuzzer -o $@ $< $(OBJECT_ARCHIVE) $(LDFLAGS_ALL) $(LDLIBS_ALL)

$(BUILD)/replay/%: tests/fuzz/%.c tests/fuzz/replay.c $(FUZZ_HEADERS) $(OBJECT_ARCHIVE)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_ALL) -o $@ $< tests/fuzz/replay.c $(OBJECT_ARCHIVE) $(LDFLAGS_ALL) $(LDLIBS_ALL)

deps:
	@scripts/install-deps $(if $(filter 1,$(VALGRIND)),valgrind)

# The sub-make evaluates pkg-config after install-deps has put the libraries in.
demo: deps
	@$(MAKE) --no-print-directory $(PROGRAM)
	@UNROLL=$(PROGRAM) scripts/demo

# README.md's example outputs and docs/helicoid.png from the current build (scripts/readme).
readme: deps
	@$(MAKE) --no-print-directory $(PROGRAM)
	@scripts/readme

check: deps
	@$(MAKE) --no-print-directory test

# tests/run-tests builds examples/ against the copy installed in
# $(INSTALL_CHECK_PREFIX) (tests/install-check) and checks that the
# libraries export ur_ names only (tests/exported-names).
test: $(PROGRAM) $(SHARED) $(UNIT_BINARIES) $(REPLAY_BINARIES)
	@rm -rf $(INSTALL_CHECK_PREFIX)
	@$(MAKE) --no-print-directory -s install PREFIX=$(INSTALL_CHECK_PREFIX) DESTDIR= >/dev/null
	@UNROLL=$(PROGRAM) UNIT_TESTS="$(UNIT_BINARIES)" REPLAYS="$(REPLAY_BINARIES)" \
		VALGRIND="$(VALGRIND)" VALGRIND_SKIP="$(VALGRIND_SKIP)" \
		EXPORTED="$(LIBRARY) $(SHARED)" \
		INSTALLED="$(INSTALL_CHECK_PREFIX)" EXAMPLE_CC="$(CC)" EXAMPLE_FLAGS="$(SANITIZE_FLAGS)" \
		tests/run-tests

# clang and libFuzzer are installed only here: make check does not need them.
fuzz:
	@scripts/install-deps fuzz
	@$(MAKE) --no-print-directory FUZZ=1 fuzz-targets
	@FUZZ_SECONDS=$(FUZZ_SECONDS) tests/fuzz/run-fuzz $(FUZZ_SOURCES:tests/fuzz/%.c=build/fuzz/fuzz/%)

fuzz-targets: $(FUZZ_BINARIES)

bench: deps
	@$(MAKE) --no-print-directory $(PROGRAM) $(BENCH_BINARIES)
	@UNROLL=$(PROGRAM) BENCHES="$(BENCH_BINARIES) bench/bench_esicup bench/bench_papercraft" \
		bench/run-benches

# A fresh unroll.pc each time: it names the PREFIX of this install.
install: $(PROGRAM) $(SHARED)
	@rm -f $(BUILD)/unroll.pc
	@$(MAKE) --no-print-directory $(BUILD)/unroll.pc
	install -d $(DESTDIR)$(BINDIR) $(DESTDIR)$(MANDIR)/man1 $(DESTDIR)$(MANDIR)/man5
	install -d $(DESTDIR)$(LIBDIR) $(DESTDIR)$(PKGCONFIGDIR) $(DESTDIR)$(INCLUDEDIR)/unroll
	install -m 755 $(PROGRAM) $(DESTDIR)$(BINDIR)/unroll
	install -m 644 $(LIBRARY) $(DESTDIR)$(LIBDIR)/libunroll.a
	install -m 755 $(SHARED_FILE) $(DESTDIR)$(LIBDIR)/$(notdir $(SHARED_FILE))
	ln -sf $(notdir $(SHARED_FILE)) $(DESTDIR)$(LIBDIR)/$(SONAME)
	ln -sf $(SONAME) $(DESTDIR)$(LIBDIR)/libunroll.so
	install -m 644 include/unroll/*.h $(DESTDIR)$(INCLUDEDIR)/unroll/
	install -m 644 $(BUILD)/unroll.pc $(DESTDIR)$(PKGCONFIGDIR)/unroll.pc
	install -m 644 man/unroll.1 $(DESTDIR)$(MANDIR)/man1/unroll.1
	install -m 644 man/unroll-profile.5 $(DESTDIR)$(MANDIR)/man5/unroll-profile.5
	install -m 644 man/unroll-job.5 $(DESTDIR)$(MANDIR)/man5/unroll-job.5
	for dir in machines materials schema; do \
		install -d $(DESTDIR)$(PROFILEDIR)/$$dir && \
		install -m 644 profiles/$$dir/* $(DESTDIR)$(PROFILEDIR)/$$dir/ || exit 1; \
	done

format:
	clang-format -i $$(git ls-files '*.c' '*.h')

clean:
	rm -rf build out

-include $(LIB_OBJECTS:.o=.d) $(CLI_OBJECTS:.o=.d)
