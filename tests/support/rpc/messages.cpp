// messages.cpp — framed messages on the judge-runner socket, and exceptions in transit.
#include "messages.hpp"

#include "common/stub.hpp"

#include <cerrno>
#include <exception>

#include <sys/socket.h>
#include <unistd.h>

namespace rt::rpc {

namespace {

void write_all(int fd, const char* data, std::size_t size) {
    while (size > 0) {
        // MSG_NOSIGNAL: a runner that is gone is an error to report, not a SIGPIPE that ends the judge.
        const ssize_t n = ::send(fd, data, size, MSG_NOSIGNAL);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) throw protocol_error("the other side of the channel is gone");
        data += n;
        size -= static_cast<std::size_t>(n);
    }
}

void read_all(int fd, char* data, std::size_t size) {
    while (size > 0) {
        const ssize_t n = ::read(fd, data, size);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) throw protocol_error("the other side of the channel is gone");
        data += n;
        size -= static_cast<std::size_t>(n);
    }
}

}  // namespace

void send_frame(int fd, std::uint8_t what, const std::string& bytes) {
    std::string frame(5, '\0');
    const std::uint32_t size = static_cast<std::uint32_t>(bytes.size() + 1);
    std::memcpy(frame.data(), &size, 4);
    frame[4] = static_cast<char>(what);
    frame += bytes;
    write_all(fd, frame.data(), frame.size());
}

void channel::send(kind what, const std::string& bytes) { send_frame(fd_, static_cast<std::uint8_t>(what), bytes); }

message channel::receive() {
    std::uint32_t size = 0;
    read_all(fd_, reinterpret_cast<char*>(&size), 4);
    if (size < 1 || size > max_message_bytes) throw protocol_error("a message of impossible length");
    std::string frame(size, '\0');
    read_all(fd_, frame.data(), size);
    const auto what = static_cast<std::uint8_t>(frame[0]);
    if (what < 1 || what > 6) throw protocol_error("a message of unknown kind");
    return {static_cast<kind>(what), frame.substr(1)};
}

std::string describe_current_exception() {
    writer w;
    exception_kind k = exception_kind::other;
    std::string text = "an exception that is not a std::exception";
    try {
        throw;
    } catch (const not_implemented& e) {
        k = exception_kind::not_implemented, text = e.what();
    } catch (const std::invalid_argument& e) {
        k = exception_kind::invalid_argument, text = e.what();
    } catch (const std::domain_error& e) {
        k = exception_kind::domain_error, text = e.what();
    } catch (const std::out_of_range& e) {
        k = exception_kind::out_of_range, text = e.what();
    } catch (const std::logic_error& e) {
        k = exception_kind::logic_error, text = e.what();
    } catch (const std::runtime_error& e) {
        k = exception_kind::runtime_error, text = e.what();
    } catch (const std::exception& e) {
        text = e.what();
    } catch (...) {
    }
    put(w, static_cast<std::uint8_t>(k));
    put(w, text.substr(0, 4096));
    return w.bytes();
}

void throw_described(const std::string& bytes, const std::function<std::string(exception_kind, const std::string&)>& retell) {
    reader r(bytes);
    std::uint8_t k = 0;
    std::string text;
    get(r, k);
    get(r, text);
    if (k < 1 || k > 7) throw protocol_error("an exception of unknown kind");
    if (r.remaining() != 0) throw protocol_error("an exception longer than its message");
    const auto what = static_cast<exception_kind>(k);
    text = retell ? retell(what, text) : text;
    switch (what) {
        case exception_kind::not_implemented: throw std::logic_error(text);  // retell() builds the stub's words
        case exception_kind::invalid_argument: throw std::invalid_argument(text);
        case exception_kind::domain_error: throw std::domain_error(text);
        case exception_kind::out_of_range: throw std::out_of_range(text);
        case exception_kind::logic_error: throw std::logic_error(text);
        case exception_kind::runtime_error: throw std::runtime_error(text);
        case exception_kind::other: break;
    }
    throw std::runtime_error(text);
}

}  // namespace rt::rpc
