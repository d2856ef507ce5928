// messages.hpp — the messages between the judge and the runner, and the exceptions that cross.
//
// One call: the judge sends `call` (the call's number, the function's name and its arguments); the runner
// runs the student's function and sends `answer` (the result) or `threw` (the exception). While a call of
// chapter 03's closest_hit, chapter 06's shade or chapter 08's traversal is outstanding, the runner sends
// `call_back` for each question the student's code asks its callback; the judge answers it
// (`call_back_answer`) and keeps waiting, so the judge sees every call the code makes (served_by_judge.hpp
// says why these are not answered in the runner). Every message about a call starts with the call's
// 32-bit number: a message about another call is garbage (judge_side.cpp, call_remote). Before its first call
// to a runner the judge sends `same_cpu`: the CPU the two share (judge_side.cpp, share_cpu).
#pragma once

#include "exact_bits.hpp"

#include <functional>
#include <string>

namespace rt::rpc {

// --- messages -------------------------------------------------------------------------------------------
// Every message is a kind byte and its bytes, framed by a 32-bit length (messages.cpp).
enum class kind : std::uint8_t {
    call = 1,             // judge -> runner: call number, function name, arguments
    answer = 2,           // runner -> judge: call number, the result
    threw = 3,            // runner -> judge: call number, exception kind, message
    same_cpu = 4,         // judge -> runner: run on this CPU (a 32-bit number), the judge's own; no answer
    call_back = 5,        // runner -> judge: call number, a callback asked (callback number, its arguments)
    call_back_answer = 6  // judge -> runner: call number, the callback's answer
};

// The exceptions that cross: tests check some of their types (std::invalid_argument for bad input).
enum class exception_kind : std::uint8_t {
    not_implemented = 1,
    invalid_argument = 2,
    domain_error = 3,
    out_of_range = 4,
    logic_error = 5,
    runtime_error = 6,
    other = 7,
};

struct message {
    kind what{};
    std::string bytes;
};

class channel {
public:
    explicit channel(int fd) : fd_(fd) {}
    void send(kind what, const std::string& bytes);
    message receive();  // throws protocol_error when the other side is gone or sends garbage
    int fd() const { return fd_; }

private:
    int fd_;
};

// One framed message (a 32-bit length, the kind byte, the bytes) written whole on fd; the channel's
// messages and the judge's reports to the grader (judge_main.cpp) are framed this way.
void send_frame(int fd, std::uint8_t what, const std::string& bytes);

// Messages larger than this are refused: a runner cannot make the judge allocate without end.
inline constexpr std::uint32_t max_message_bytes = 64u << 20;


// The exception being handled (call inside a catch block), as the bytes of a `threw` message.
std::string describe_current_exception();

// Throws the exception a `threw` message describes, with the same standard type, so a test's
// catch (const std::invalid_argument&) still works. retell(kind, text) may replace the text
// (the judge never shows a student's own words in hidden feedback).
[[noreturn]] void throw_described(const std::string& bytes,
                                  const std::function<std::string(exception_kind, const std::string&)>& retell);

}  // namespace rt::rpc
