// main() of every judge (chNN_public_judge, chNN_hidden_judge): doctest, plus the verdict for the grader.
//
// The judge holds the course's tests and no student code, so what it reports is the verdict: when the
// grader passes RT_JUDGE_REPORT_FD, a doctest listener writes `cases failed asserts failed-asserts`
// there once the run is over. Nothing the runner does can reach this descriptor.
#define DOCTEST_CONFIG_IMPLEMENT
#include <doctest/doctest.h>

#include "judge.hpp"

#include <csignal>
#include <cstdlib>
#include <string>

#include <unistd.h>

namespace {

int report_fd = -1;

struct verdict_listener : doctest::IReporter {
    explicit verdict_listener(const doctest::ContextOptions&) {}

    void test_run_end(const doctest::TestRunStats& stats) override {
        if (report_fd < 0) return;
        const std::string line = std::to_string(stats.numTestCasesPassingFilters) + " " +
                                 std::to_string(stats.numTestCasesFailed) + " " + std::to_string(stats.numAsserts) +
                                 " " + std::to_string(stats.numAssertsFailed) + "\n";
        (void)!::write(report_fd, line.data(), line.size());
        ::close(report_fd);
        report_fd = -1;
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

REGISTER_LISTENER("rt_judge_verdict", 1, verdict_listener);

int main(int argc, char** argv) {
#if defined(RT_JUDGE_PUBLIC)
    rt::rpc::show_student_messages = true;  // public feedback keeps the student's own exception messages
#endif
    std::signal(SIGPIPE, SIG_IGN);  // a runner that is gone is reported by the channel, not by a signal
    if (const char* fd = std::getenv("RT_JUDGE_REPORT_FD")) report_fd = std::atoi(fd);
    doctest::Context context(argc, argv);
    return context.run();
}
