// runner_main.cpp — main() of every chNN_runner: answer the judge's calls with the student's code.
//
// One runner serves a chapter's cases one after another (the grader hands its socket to each judge in
// turn) until the grader closes the channel; whatever state the student's code keeps lives on.
//
// `chNN_runner --probe` only starts and exits: the grader runs it once per chapter, so a static
// initialiser that hangs or crashes fails the chapter's tests at once instead of one timeout per test.
#include "runner_side.hpp"

#include <cstdlib>
#include <cstring>
#include <map>

#include <sched.h>
#include <unistd.h>

namespace rt::rpc {

namespace {

std::map<std::string, handler>& handlers() {
    static std::map<std::string, handler> table;
    return table;
}

int judge_fd = -1;
std::uint32_t current_call = 0;  // the number of the call being answered (judge_side.cpp, call_remote)

std::string numbered(std::uint32_t number, const std::string& bytes) {
    writer w;
    put(w, number);
    w.raw(bytes.data(), bytes.size());
    return w.bytes();
}

// Runs one call from the judge (its number, the function's name, the arguments) and sends back its
// answer or its exception, under the call's number.
void answer(channel& ch, const std::string& bytes) {
    reader r(bytes);
    get(r, current_call);
    std::string function;
    get(r, function);
    const auto found = handlers().find(function);
    const std::string rest(bytes.substr(sizeof current_call + 4 + function.size()));
    try {
        if (found == handlers().end()) throw std::logic_error("the runner has no function " + function);
        const std::string result = found->second(rest);
        ch.send(kind::answer, numbered(current_call, result));
    } catch (const protocol_error&) {
        throw;
    } catch (...) {
        ch.send(kind::threw, numbered(current_call, describe_current_exception()));
    }
}

// The judge's CPU (judge_side.cpp, share_cpu): the two take turns, and waking another CPU for every turn
// costs more than the call.
void run_on(const std::string& bytes) {
    reader r(bytes);
    std::int32_t cpu = -1;
    get(r, cpu);
    if (cpu < 0 || cpu >= CPU_SETSIZE) return;
    cpu_set_t one;
    CPU_ZERO(&one);
    CPU_SET(cpu, &one);
    (void)::sched_setaffinity(0, sizeof one, &one);  // refused: the calls are only slower
}

}  // namespace

// Called by an object callback inside the student's code: asks the judge and waits for its answer.
std::string runner_call_back(std::uint32_t id, const std::string& arguments) {
    channel ch(judge_fd);
    writer w;
    put(w, id);
    w.raw(arguments.data(), arguments.size());
    const std::uint32_t asking = current_call;  // the call this question belongs to
    ch.send(kind::call_back, numbered(asking, w.bytes()));
    for (;;) {
        const message m = ch.receive();
        if (m.what == kind::call_back_answer) {
            reader r(m.bytes);
            std::uint32_t about = 0;
            get(r, about);
            if (about != asking) throw protocol_error("a callback's answer about another call");
            return m.bytes.substr(sizeof about);
        }
        // While the judge answers the callback it may call an exercise function of an earlier chapter:
        // in a student kit the judge has no solutions, so the test's own helpers (chapter 06's served
        // occlusion test asks chapter 02's sphere) are forwarded here too. The call is answered first,
        // as any other (under its own number), and then the callback's answer comes.
        if (m.what == kind::same_cpu) {
            run_on(m.bytes);
        } else if (m.what == kind::call) {
            answer(ch, m.bytes);
            current_call = asking;
        } else {
            throw protocol_error("a message the runner did not expect");
        }
    }
}

bool serve_erased(const std::string& function, handler h) {
    handlers()[function] = std::move(h);
    return true;
}

}  // namespace rt::rpc

int main(int argc, char** argv) {
    using namespace rt::rpc;
    if (argc > 1 && std::strcmp(argv[1], "--probe") == 0) return 0;
    const char* fd = std::getenv("RT_RPC_FD");
    if (fd == nullptr) {
        static const char text[] = "chNN_runner answers a judge's calls: run a judge (chNN_public_judge) with "
                                   "RT_RUNNER=this program instead\n";
        (void)!::write(2, text, sizeof text - 1);
        return 2;
    }
    judge_fd = std::atoi(fd);
    channel ch(judge_fd);
    try {
        for (;;) {
            const message m = ch.receive();
            if (m.what == kind::same_cpu) {
                run_on(m.bytes);
                continue;
            }
            if (m.what != kind::call) break;
            answer(ch, m.bytes);
        }
    } catch (const protocol_error&) {
        // The grader closed the channel: the chapter's tests are over (or this runner was replaced).
    }
    // _exit: no static destructor or atexit handler of the student's runs after the last answer.
    ::_exit(0);
}
