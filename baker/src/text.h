// Private to the baker: small text helpers for error messages.
#pragma once

#include <charconv>
#include <string>
#include <string_view>

namespace lt {

// Shortest decimal text that reads back as `f` (locale-independent).
inline std::string formatFloat(float f) {
    char buf[32];
    auto res = std::to_chars(buf, buf + sizeof buf, f);
    return std::string(buf, res.ptr);
}

// How much of the input a message may quote.
inline constexpr size_t kMaxExcerpt = 80;

// At most `most` bytes of `s`, cut before a UTF-8 continuation byte (so a message
// stays valid UTF-8 for the JSON report), "..." appended when cut.
inline std::string excerpt(std::string_view s, size_t most = kMaxExcerpt) {
    if (s.size() <= most) return std::string(s);
    size_t cut = most;
    while (cut > 0 && (static_cast<unsigned char>(s[cut]) & 0xC0) == 0x80) --cut;
    return std::string(s.substr(0, cut)) + "...";
}

// A third-party parser's message (nlohmann/json, tinygltf) with the input it quotes
// cut to excerpts: what follows nlohmann's "last read: '" (the token read so far,
// e.g. a whole unterminated data URI), and every run of more than kMaxExcerpt
// non-blank bytes (a base64 payload, a long name).
inline std::string shortenQuotes(std::string_view message) {
    const std::string_view lastRead = "last read: '";
    if (const size_t at = message.find(lastRead); at != std::string_view::npos) {
        std::string_view token = message.substr(at + lastRead.size());
        if (!token.empty() && token.back() == '\'') token.remove_suffix(1);
        return shortenQuotes(message.substr(0, at)) + std::string(lastRead) + excerpt(token) + "'";
    }
    std::string out;
    for (size_t i = 0; i < message.size();) {
        size_t j = i;
        while (j < message.size() && message[j] != ' ' && message[j] != '\n') ++j;
        out += excerpt(message.substr(i, j - i));
        if (j < message.size()) out += message[j++];
        i = j;
    }
    return out;
}

}  // namespace lt
