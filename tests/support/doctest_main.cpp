// The one main() shared by every doctest executable of the course.
//
// It also carries the autograder's result channel (tools/grader/README.md).
// The grader must decide pass or fail itself, and the student's code runs in
// this very process, so anything printed on stdout could be forged (a fake
// "Status: SUCCESS!", or exit(0) before the test ends). When the grader runs a
// test it passes two file descriptors in the environment:
//   RT_GRADER_NONCE_FD   a pipe holding a fresh random word, read once here,
//                        before the student's own static initialisers run;
//   RT_GRADER_REPORT_FD  where doctest's final counts are written, after the
//                        test case has finished, prefixed by that word.
// A test passes only if the report arrives with the right word and says one
// test case ran and nothing failed. Outside the grader neither variable is set
// and this file behaves like plain doctest.
#define DOCTEST_CONFIG_IMPLEMENT_WITH_MAIN
#include <doctest/doctest.h>

#include <cstdlib>
#include <string>

#include <unistd.h>

namespace {

// Plain arrays, not std::string: they are ready before any constructor runs,
// so the early reader below cannot be undone by a later static initialiser.
char grader_nonce[128] = {};
int grader_report_fd = -1;

int fd_from_environment(const char* name) {
    const char* value = std::getenv(name);
    if (value == nullptr) return -1;
    char* end = nullptr;
    const long fd = std::strtol(value, &end, 10);
    return (end != value && *end == '\0' && fd > 2 && fd < 1024) ? static_cast<int>(fd) : -1;
}

// Priority 101 is the earliest a program may ask for: the word is taken out of
// the pipe before ordinary static initialisers (including a student's) run.
__attribute__((constructor(101))) void take_grader_channel() {
    const int nonce_fd = fd_from_environment("RT_GRADER_NONCE_FD");
    grader_report_fd = fd_from_environment("RT_GRADER_REPORT_FD");
    unsetenv("RT_GRADER_NONCE_FD");
    unsetenv("RT_GRADER_REPORT_FD");
    if (nonce_fd < 0) return;
    size_t length = 0;
    ssize_t n = 0;
    while (length + 1 < sizeof grader_nonce &&
           (n = read(nonce_fd, grader_nonce + length, sizeof grader_nonce - 1 - length)) > 0)
        length += static_cast<size_t>(n);
    grader_nonce[length] = '\0';
    close(nonce_fd);
}

// A doctest listener: it prints nothing, and reports the run's counts to the
// grader once the run is over.
struct grader_listener : doctest::IReporter {
    explicit grader_listener(const doctest::ContextOptions&) {}

    void test_run_end(const doctest::TestRunStats& stats) override {
        if (grader_report_fd < 0 || grader_nonce[0] == '\0') return;
        const std::string line = std::string(grader_nonce) + " " + std::to_string(stats.numTestCasesPassingFilters) + " " +
                                 std::to_string(stats.numTestCasesFailed) + " " + std::to_string(stats.numAsserts) +
                                 " " + std::to_string(stats.numAssertsFailed) + "\n";
        const ssize_t written = write(grader_report_fd, line.data(), line.size());
        (void)written;  // nothing to do if the grader is gone: the test then fails
        close(grader_report_fd);
        grader_report_fd = -1;
    }

    void report_query(const doctest::QueryData&) override {}
    void test_run_start() override {}
    void test_case_start(const doctest::TestCaseData&) override {}
    void test_case_reenter(const doctest::TestCaseData&) override {}
    void test_case_end(const doctest::CurrentTestCaseStats&) override {}
    void test_case_exception(const doctest::TestCaseException&) override {}
    void subcase_start(const doctest::SubcaseSignature&) override {}
    void subcase_end() override {}
    void log_assert(const doctest::AssertData&) override {}
    void log_message(const doctest::MessageData&) override {}
    void test_case_skipped(const doctest::TestCaseData&) override {}
};

}  // namespace

REGISTER_LISTENER("rt_grader_channel", 1, grader_listener);
