// judge_side.hpp — the judge's side of a call: a test calls an exercise function, the judge's stub for that
// function (tests/support/rpc/chNN.cpp) sends the arguments to the runner and returns its answer.
//
// The judge is a doctest program built from the course's tests and this library, without any student
// code: its verdict cannot be touched by the student's code, which only ever sees arguments and only
// ever gives back answers (exact bits) or exceptions.
#pragma once

#include "messages.hpp"

#include <cstdint>
#include <string>

namespace rt::rpc {

// True in a public judge (its main() sets it): feedback may show the student's own exception messages
// and the numbers of a callback's call that broke a rule. A hidden judge shows neither: a student's
// text, or a number the student's code chose, could carry a hidden input out.
extern bool public_feedback;

// Raised in the judge when the runner stops answering (crash, exit, limit, garbage on the channel). The
// runner is then marked broken: the case fails, and the grader hands the next case a fresh runner.
struct runner_gone : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// The judge's link to the grader when the grader runs it (RT_JUDGE_CONTROL_FD), or -1 (by hand, ctest).
// One judge process runs all the cases it is given; judge_main.cpp reports each one on this socket.
int control_fd();

// At the start of every test case: tells the grader which case begins and whether the runner broke, and
// takes the runner the grader gives for it (a fresh one after a crash, a hang or garbage on the channel).
// Without the grader, RT_RUNNER's program is started again when the previous one broke.
void begin_case(const std::string& name);

// Whether the runner stopped answering during the current case: that case fails whatever its checks
// said (a CHECK_THROWS must not count the runner's crash as the exception it expected).
bool runner_broke_in_case();

// A number that changes whenever the judge's runner is replaced: what a runner remembers from earlier
// calls (chapter 08's last tree, ch08.cpp) is gone with it.
std::uint64_t runner_generation();

// Callbacks registered while one call's arguments are written live exactly as long as that call.
class callback_scope {
public:
    callback_scope();
    ~callback_scope();
    callback_scope(const callback_scope&) = delete;
    callback_scope& operator=(const callback_scope&) = delete;

private:
    std::size_t mark_;
};

// Sends one call, answers the runner's call_back messages until the answer comes; returns its bytes.
std::string call_remote(const std::string& function, const std::string& arguments);

// The runner's answer to `function` is not a value of the type it should be: the runner is broken
// (marked so: the grader replaces it before the next case, and this case fails). Throws runner_gone.
[[noreturn]] void runner_sent_garbage(const std::string& function, const std::string& why);

template <class T>
std::string call_name(const char* function) {
    return std::string(function) + (sizeof(T) == sizeof(float) ? "<float>" : "<double>");
}

template <class R, class... A>
R forward(const std::string& function, const A&... arguments) {
    callback_scope scope;
    writer w;
    (put(w, arguments), ...);
    const std::string answer = call_remote(function, w.bytes());
    reader r(answer);
    R result{};
    try {
        get(r, result);
        if (r.remaining() != 0) throw protocol_error("an answer longer than its value");
    } catch (const protocol_error& e) {
        runner_sent_garbage(function, std::string("its answer is not a value of the right type (") + e.what() +
                                          "; did your code write to the grader's channel?)");
    }
    return result;
}

}  // namespace rt::rpc
