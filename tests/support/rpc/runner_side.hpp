// runner_side.hpp — the runner's side: it holds the student's exercise code and only answers calls.
//
// Each chapter's table (tests/support/rpc/chNN.cpp, compiled with RT_RPC_RUNNER) registers its
// functions with serve(); the runner's main() (runner_main.cpp) then answers the judge's calls until the
// judge closes the channel. The runner decides nothing: whatever it prints, writes or returns as its
// exit status is ignored by the grader; only its answers reach the tests, in the judge.
#pragma once

#include "messages.hpp"

#include <string>
#include <tuple>
#include <type_traits>

namespace rt::rpc {

using handler = std::function<std::string(const std::string& arguments)>;

bool serve_erased(const std::string& function, handler h);

// Registers a student's function: its arguments are read from the call, its result sent back.
template <class R, class... A>
bool serve(const std::string& function, R (*f)(A...)) {
    return serve_erased(function, [f](const std::string& bytes) {
        reader r(bytes);
        std::tuple<std::decay_t<A>...> arguments;
        std::apply([&r](auto&... a) { (get(r, a), ...); }, arguments);
        if (r.remaining() != 0) throw protocol_error("a call with more arguments than the function takes");
        writer w;
        put(w, std::apply(f, arguments));
        return w.bytes();
    });
}

}  // namespace rt::rpc
