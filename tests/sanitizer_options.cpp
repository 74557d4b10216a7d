// Linked into every program of the sanitizer build (WHATNEXT_SANITIZE): the sanitizers ask for
// these defaults at start-up, so tests, the whatnext command they run and the fuzzers all behave
// the same without environment variables.
extern "C" {

// Fontconfig (through Cairo and PLplot) keeps its font cache, and libltdl the drivers PLplot
// loads, for the life of the process.
const char* __lsan_default_suppressions() { return "leak:libfontconfig.so\nleak:libltdl.so\n"; }

// Without a report to make, say nothing: the table of suppressions used, printed at exit, turned a
// whatnext error after drawing (a GIF that could not be written) into more than one line.
const char* __lsan_default_options() { return "print_suppressions=0"; }

const char* __ubsan_default_options() { return "print_stacktrace=1:halt_on_error=1"; }

const char* __asan_default_options() { return "detect_leaks=1:strict_init_order=1"; }
}
