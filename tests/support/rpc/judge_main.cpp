// main() of every judge (chNN_public_judge, chNN_hidden_judge): doctest, plus the verdicts for the grader.
//
// The judge holds the course's tests and no student code, so what it reports is the verdict. Under the
// grader (RT_JUDGE_CONTROL_FD) one judge process runs all the cases it is given, and a doctest listener
// reports each on the control socket:
//   B  at the case's start: the runner's state and the case's name (judge_side.cpp, begin_case), after which
//      the grader answers with the runner to use;
//   E  once the case is over: "failed asserts failed-asserts runner-broke", a newline, and doctest's
//      report of that case (the feedback; doctest writes into a buffer, not to the terminal).
// Nothing the runner does can reach this socket: the grader created it and gave it to the judge alone.
#define DOCTEST_CONFIG_IMPLEMENT
#include <doctest/doctest.h>

#include "judge_side.hpp"

#include <csignal>
#include <cstdlib>
#include <sstream>
#include <string>

namespace {

constexpr std::size_t case_output_cap = 256 * 1024;  // feedback beyond this is never shown anyway

std::ostringstream case_output;  // doctest's report of the current case
std::string finished;            // the E line of the case that just ended, until its report is complete

// Sends the previous case's verdict with everything doctest wrote about it. Called when the next case
// starts or the run ends: the console reporter writes its part of a case's end after the listeners.
void send_finished() {
    if (finished.empty() || rt::rpc::control_fd() < 0) return;
    std::string report = case_output.str();
    if (report.size() > case_output_cap) report = report.substr(0, case_output_cap) + "\n(report cut here)\n";
    case_output.str("");
    try {
        rt::rpc::send_frame(rt::rpc::control_fd(), 'E', finished + "\n" + report);
    } catch (const std::exception&) {
        std::_Exit(4);  // the grader is gone
    }
    finished.clear();
}

struct verdict_listener : doctest::IReporter {
    explicit verdict_listener(const doctest::ContextOptions&) {}

    void test_case_start(const doctest::TestCaseData& tc) override {
        send_finished();
        case_output.str("");
        rt::rpc::begin_case(tc.m_name);
    }

    void test_case_end(const doctest::CurrentTestCaseStats& st) override {
        finished = std::to_string(st.testCaseSuccess ? 0 : 1) + " " + std::to_string(st.numAssertsCurrentTest) + " " +
                   std::to_string(st.numAssertsFailedCurrentTest) + " " +
                   std::to_string(rt::rpc::runner_broke_in_case() ? 1 : 0);
    }

    void test_run_end(const doctest::TestRunStats&) override { send_finished(); }

    void report_query(const doctest::QueryData&) override {}
    void test_run_start() override {}
    void test_case_reenter(const doctest::TestCaseData&) override {}
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
    rt::rpc::public_feedback = true;  // public feedback keeps the student's own messages and a rule's numbers
#endif
    std::signal(SIGPIPE, SIG_IGN);  // a runner that is gone is reported by the channel, not by a signal
    doctest::Context context(argc, argv);
    if (rt::rpc::control_fd() >= 0) context.setCout(&case_output);
    return context.run();
}
