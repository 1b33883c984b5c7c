#include "core/json_input.hpp"

#include <cstdint>
#include <limits>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <set>
#include <stdexcept>
#include <vector>

namespace rapid {

namespace {

// What the parser callback throws; it never leaves parse_json_text.
struct Refused {
  std::string why;
};

// A parser message names the position and the token; the token can be a whole long string.
std::string shortened(std::string text, std::size_t max = 160) {
  if (text.size() > max) text = text.substr(0, max) + "…";
  return text;
}

}  // namespace

nlohmann::json parse_json_text(const std::string& text) {
  std::vector<std::set<std::string>> keys;  // one set per open object
  // Where the parser is: the key of each open object ("" before its first key), "[]" for an array.
  std::vector<std::string> path;
  const auto check = [&](int depth, nlohmann::json::parse_event_t event, nlohmann::json& parsed) {
    using E = nlohmann::json::parse_event_t;
    if ((event == E::object_start || event == E::array_start) && depth >= kMaxJsonDepth)
      throw Refused{"nests deeper than " + std::to_string(kMaxJsonDepth) + " levels"};
    if (event == E::object_start) keys.emplace_back();
    if (event == E::object_end && !keys.empty()) keys.pop_back();
    if (event == E::key && !keys.empty() && !keys.back().insert(parsed.get<std::string>()).second)
      throw Refused{"duplicate key '" + shortened(parsed.get<std::string>(), 60) + "'"};
    if (event == E::object_start || event == E::array_start) path.push_back(event == E::array_start ? "[]" : "");
    if ((event == E::object_end || event == E::array_end) && !path.empty()) path.pop_back();
    if (event == E::key && !path.empty()) path.back() = parsed.get<std::string>();
    return true;
  };
  try {
    return nlohmann::json::parse(text, check);
  } catch (const Refused& r) {
    throw std::invalid_argument(r.why);
  } catch (const nlohmann::json::parse_error& e) {
    throw std::invalid_argument("not valid JSON: " + shortened(e.what()));
  } catch (const nlohmann::json::out_of_range&) {
    // The one range error of parsing: a number beyond a double (1e400). Name the field.
    std::string field;
    for (const std::string& p : path) field += p == "[]" ? "[]" : (field.empty() ? "" : ".") + shortened(p, 60);
    throw std::invalid_argument((field.empty() ? std::string("a number") : "'" + field + "'") +
                                " is too large for a double");
  }
}

nlohmann::json read_json_input(const std::string& path, std::size_t max_bytes) {
  // open(2) and read(2), not a stream: a directory, a FIFO or /dev/zero must end with a message.
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (fd < 0) {
    if (errno == ENOENT) throw std::invalid_argument("no such file");
    throw std::invalid_argument(std::string("cannot read: ") + std::strerror(errno));
  }
  struct stat st {};
  if (::fstat(fd, &st) == 0 && S_ISDIR(st.st_mode)) {
    ::close(fd);
    throw std::invalid_argument("is a directory, not a JSON file");
  }
  std::string text;
  char buf[1 << 16];
  for (;;) {
    const ssize_t n = ::read(fd, buf, sizeof buf);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      const int err = errno;
      ::close(fd);
      throw std::invalid_argument(std::string("cannot read: ") + std::strerror(err));
    }
    if (n == 0) break;
    text.append(buf, static_cast<std::size_t>(n));
    if (text.size() > max_bytes) {
      ::close(fd);
      throw std::invalid_argument("is larger than " + std::to_string(max_bytes >> 20) + " MiB; not a file rapid reads");
    }
  }
  ::close(fd);
  return parse_json_text(text);
}

std::optional<long long> json_integer(const nlohmann::json& v) {
  if (!v.is_number_integer()) return std::nullopt;
  if (v.is_number_unsigned()) {
    const std::uint64_t u = v.get<std::uint64_t>();
    if (u > static_cast<std::uint64_t>(std::numeric_limits<long long>::max())) return std::nullopt;
    return static_cast<long long>(u);
  }
  return v.get<long long>();
}

std::string json_excerpt(const nlohmann::json& value, std::size_t max) {
  std::string text = value.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  if (text.size() > max) text = text.substr(0, max) + "…";
  return text;
}

}  // namespace rapid
