// judge_side.cpp — the judge's connection to the runner.
//
// The grader runs one judge process for many test cases and gives it the runner over a control socket
// (RT_JUDGE_CONTROL_FD): at the start of each case the judge says which case begins and whether its
// runner broke, and the grader answers "go on" or passes a fresh runner's socket (SCM_RIGHTS). Without
// the grader, RT_RUNNER=path/to/chNN_runner makes the judge start the runner itself (for the course's own
// tests and for debugging), and start it again after it broke.
#include "judge_side.hpp"

#include <cctype>
#include <cerrno>
#include <cstring>
#include <cstdlib>
#include <vector>

#include <sched.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

namespace rt::rpc {

bool public_feedback = false;

namespace {

struct connection {
    int fd = -1;
    bool cpu_shared = false;     // the runner on fd was told to run on the judge's CPU
    std::uint64_t generation = 0;  // counts the runners this judge was given
    std::string broken;          // why the runner is gone; empty while it answers
    bool broke_in_case = false;  // it broke during the current test case
};

int start_runner(const char* path) {
    int ends[2];
    if (::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, ends) != 0) return -1;
    const pid_t child = ::fork();
    if (child == 0) {
        ::dup2(ends[1], 3);  // dup2 clears close-on-exec on the copy
        ::setenv("RT_RPC_FD", "3", 1);
        ::execl(path, path, static_cast<char*>(nullptr));
        ::_exit(127);
    }
    ::close(ends[1]);
    if (child > 0) return ends[0];
    ::close(ends[0]);
    return -1;
}

const char* no_runner = "no runner: the grader gives one; by hand, set RT_RUNNER=build/.../chNN_runner";

connection& runner() {
    static connection c = [] {
        connection made;
        if (control_fd() < 0) {
            if (const char* path = std::getenv("RT_RUNNER")) made.fd = start_runner(path);
        }
        if (made.fd < 0) made.broken = no_runner;  // under the grader: the first case brings one
        return made;
    }();
    return c;
}

// The grader's one-byte answer to a case's start: 'G' (go on with the runner you have) or 'R' with a
// fresh runner's socket attached. Returns the kind, and the descriptor in fd (-1 when none came).
char receive_reply(int control, int& fd) {
    char what = 0;
    alignas(cmsghdr) char space[CMSG_SPACE(sizeof(int))];
    for (;;) {
        iovec io{&what, 1};
        msghdr m{};
        m.msg_iov = &io;
        m.msg_iovlen = 1;
        m.msg_control = space;
        m.msg_controllen = sizeof space;
        fd = -1;
        const ssize_t n = ::recvmsg(control, &m, MSG_CMSG_CLOEXEC);
        if (n < 0 && errno == EINTR) continue;
        if (n != 1) return 0;
        for (cmsghdr* c = CMSG_FIRSTHDR(&m); c != nullptr; c = CMSG_NXTHDR(&m, c)) {
            if (c->cmsg_level == SOL_SOCKET && c->cmsg_type == SCM_RIGHTS && c->cmsg_len == CMSG_LEN(sizeof(int)))
                std::memcpy(&fd, CMSG_DATA(c), sizeof(int));
        }
        return what;
    }
}

// "ch01::intersect_unit_sphere<float>" -> "intersect_unit_sphere", as the student wrote it.
std::string plain_name(const std::string& function) {
    std::string name = function.substr(0, function.find('<'));
    const auto colons = name.rfind("::");
    return colons == std::string::npos ? name : name.substr(colons + 2);
}

// A student's text, made safe to print in one line of feedback.
std::string one_safe_line(const std::string& text) {
    std::string out;
    static const char hex[] = "0123456789abcdef";
    for (char c : text.substr(0, 300)) {
        const auto byte = static_cast<unsigned char>(c);
        if (byte >= 0x20 && byte < 0x7f) {
            out += c;
        } else {  // no control character reaches a terminal: \xNN, as the grader's summary writes them
            out += "\\x";
            out += hex[byte >> 4];
            out += hex[byte & 15];
        }
    }
    return out;
}

// "ch01::intersect_unit_sphere<float>" -> "chapter 01", from the judge's own name of the call.
std::string chapter_of(const std::string& function) {
    if (function.size() >= 4 && function.compare(0, 2, "ch") == 0 && std::isdigit(static_cast<unsigned char>(function[2])) &&
        std::isdigit(static_cast<unsigned char>(function[3])))
        return "chapter " + function.substr(2, 2);
    return "this chapter";
}

// What the test sees of an exception thrown by the student's code. "not implemented yet" is told in the
// judge's words only (the chapter and the function the judge called): its text in the runner is the
// student's to choose, and digits there could carry a hidden input out.
std::string retell(const std::string& function, exception_kind k, const std::string& text) {
    const std::string name = plain_name(function);
    if (k == exception_kind::not_implemented) return "not implemented yet: " + chapter_of(function) + ", " + name;
    if (public_feedback) return one_safe_line(text);
    return "your " + name + " threw an exception (its message is not shown for hidden tests)";
}

// The judge and the runner take turns (a call, then its answer), so one CPU serves both. On separate
// CPUs every turn wakes the other CPU, and on a virtual machine whose idle CPU sleeps that costs more
// than the call itself: measured 3x slower with the two pinned apart (tools/grader/README.md,
// "Measured"). So the judge stays on the CPU it starts on and asks each runner to join it. Only a
// speed matter: a runner that ignores it changes no answer.
int judge_cpu() {
    static const int cpu = [] {
        const int here = ::sched_getcpu();
        if (here < 0) return -1;
        cpu_set_t one;
        CPU_ZERO(&one);
        CPU_SET(here, &one);
        return ::sched_setaffinity(0, sizeof one, &one) == 0 ? here : -1;
    }();
    return cpu;
}

void share_cpu(connection& c, channel& ch) {
    if (c.cpu_shared) return;
    c.cpu_shared = true;
    const int cpu = judge_cpu();
    if (cpu < 0) return;
    writer w;
    put(w, std::int32_t(cpu));
    ch.send(kind::same_cpu, w.bytes());
}

[[noreturn]] void gone(connection& c, const std::string& function, const std::string& why) {
    c.broke_in_case = true;
    c.broken = "the runner (the process that runs your code) stopped answering during a call to " +
               plain_name(function) + ": " + why;
    throw runner_gone(c.broken);
}

}  // namespace

int control_fd() {
    static const int fd = [] {
        const char* text = std::getenv("RT_JUDGE_CONTROL_FD");
        return text != nullptr ? std::atoi(text) : -1;
    }();
    return fd;
}

void begin_case(const std::string& name) {
    connection& c = runner();
    c.broke_in_case = false;
    const int control = control_fd();
    if (control < 0) {
        const char* path = std::getenv("RT_RUNNER");
        if (!c.broken.empty() && path != nullptr) {
            if (c.fd >= 0) ::close(c.fd);
            c.fd = start_runner(path);
            c.cpu_shared = false;
            ++c.generation;
            c.broken = c.fd < 0 ? no_runner : "";
        }
        return;
    }
    // "B", then 1 when the runner this judge was given broke (the grader replaces it), then the case's name.
    const bool broke = c.fd >= 0 && !c.broken.empty();
    send_frame(control, 'B', (broke ? "1" : "0") + name);
    int fd = -1;
    const char what = receive_reply(control, fd);
    if (what == 'R' && fd >= 0) {
        if (c.fd >= 0) ::close(c.fd);
        c.fd = fd;
        c.cpu_shared = false;
        ++c.generation;
        c.broken.clear();
    } else if (what != 'G') {
        if (fd >= 0) ::close(fd);
        std::_Exit(4);  // the grader is gone or wants no more cases: nothing left to report to
    }
}

bool runner_broke_in_case() { return runner().broke_in_case; }

std::uint64_t runner_generation() { return runner().generation; }

namespace {
std::vector<erased_callback>& callbacks() {
    static std::vector<erased_callback> kept;
    return kept;
}
}  // namespace

callback_scope::callback_scope() : mark_(callbacks().size()) {}
callback_scope::~callback_scope() { callbacks().resize(mark_); }

std::uint32_t judge_keep_callback(erased_callback f) {
    callbacks().push_back(std::move(f));
    return static_cast<std::uint32_t>(callbacks().size() - 1);
}

// A call_back from the runner: the callback's number and its arguments, answered from the judge's own
// copy. Whatever the runner sent is only data here: an unknown number or short arguments end the runner.
std::string answer_call_back(reader& in) {
    std::uint32_t id = 0;
    get(in, id);
    if (id >= callbacks().size()) throw protocol_error("a callback that was never given");
    writer out;
    callbacks()[id](in, out);
    if (in.remaining() != 0) throw protocol_error("a callback's arguments longer than expected");
    return out.bytes();
}

// Every call has a number, and every message the runner sends about it starts with that number: an
// answer left over from another call (a second answer, one the judge gave up on) is garbage, not the
// answer to this call.
std::uint32_t next_call_number() {
    static std::uint32_t last = 0;
    return ++last;
}

std::string call_remote(const std::string& function, const std::string& arguments) {
    connection& c = runner();
    if (!c.broken.empty()) throw runner_gone(c.broken);
    channel ch(c.fd);
    const std::uint32_t number = next_call_number();
    try {
        share_cpu(c, ch);
        writer call;
        put(call, number);
        put(call, function);
        call.raw(arguments.data(), arguments.size());
        ch.send(kind::call, call.bytes());
        for (;;) {
            const message m = ch.receive();
            reader in(m.bytes);
            std::uint32_t about = 0;
            get(in, about);
            if (about != number) throw protocol_error("a message about another call");
            const std::string rest = m.bytes.substr(sizeof about);
            if (m.what == kind::answer) return rest;
            if (m.what == kind::call_back) {
                std::string reply;
                try {
                    reply = answer_call_back(in);
                } catch (const protocol_error&) {
                    throw;
                } catch (...) {
                    // The callback could not answer (in a student kit it may ask an earlier chapter's
                    // function, forwarded to the runner, which threw): the runner now waits for an answer
                    // that never comes, so nobody gets it again. The callback's own exception goes on.
                    c.broke_in_case = true;
                    if (c.broken.empty())
                        c.broken = "the runner was left waiting for a callback's answer during a call to " +
                                   plain_name(function);
                    throw;
                }
                writer answer;
                put(answer, number);
                answer.raw(reply.data(), reply.size());
                ch.send(kind::call_back_answer, answer.bytes());
                continue;
            }
            if (m.what != kind::threw) throw protocol_error("a message the judge did not ask for");
            throw_described(rest, [&](exception_kind k, const std::string& t) { return retell(function, k, t); });
        }
    } catch (const protocol_error& e) {
        gone(c, function, e.what());
    }
}

void runner_sent_garbage(const std::string& function, const std::string& why) { gone(runner(), function, why); }

}  // namespace rt::rpc
