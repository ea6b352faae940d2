// The JSON parser's events turned into the line of each value and the first duplicate key.
#include "json_layout.hpp"

#include "scene_reading.hpp"

#include <algorithm>
#include <cstddef>
#include <iterator>
#include <map>
#include <string>
#include <vector>

namespace panelrad::io_detail {

namespace {

/// A character iterator over the JSON text that records how far nlohmann's lexer has read: the
/// parser callback then knows where each key and value ends, and so its line.
class TrackedChar {
 public:
  using iterator_category = std::input_iterator_tag;
  using value_type = char;
  using difference_type = std::ptrdiff_t;
  using pointer = const char*;
  using reference = const char&;
  TrackedChar(const char* p, const char** read) : p_(p), read_(read) {}
  reference operator*() const { return *p_; }
  TrackedChar& operator++() {
    *read_ = ++p_;
    return *this;
  }
  TrackedChar operator++(int) {
    TrackedChar before = *this;
    ++*this;
    return before;
  }
  friend bool operator==(const TrackedChar& a, const TrackedChar& b) { return a.p_ == b.p_; }

 private:
  const char* p_;
  const char** read_;
};

/// Records a JsonLayout from nlohmann's parse events: each container keeps its path, the index of
/// its next element or its current key, and the lines of its keys (for duplicates).
class JsonLayoutRecorder {
 public:
  JsonLayoutRecorder(const std::string& text, JsonLayout& layout)
      : begin_(text.data()), counted_(text.data()), layout_(layout) {}

  /// One parse event; `read` is one past the last character the lexer has taken.
  void on_event(nlohmann::json::parse_event_t event, Json& parsed, const char* read) {
    using Event = nlohmann::json::parse_event_t;
    switch (event) {
      case Event::object_start:
      case Event::array_start: {
        const long at = line_before(read);
        const std::string path = child_path();
        record(path, at);
        stack_.push_back(Frame{event == Event::array_start, path, 0, "", {}});
        break;
      }
      case Event::object_end:
      case Event::array_end:
        if (!stack_.empty()) stack_.pop_back();
        break;
      case Event::key:
        on_key(parsed.get<std::string>(), line_before(read));
        break;
      case Event::value: {
        // A number is ended by the character after it, which the lexer has read already.
        const long at = line_before(parsed.is_number() && read > begin_ ? read - 1 : read);
        record(child_path(), at);
        break;
      }
    }
  }

 private:
  struct Frame {
    bool is_array = false;
    std::string path;
    std::size_t next_index = 0;
    std::string key;
    std::map<std::string, long> key_lines;
  };
  static constexpr std::size_t kRecordedDepth = 3;  // root object, "facets" array, facet entry

  // The line of the character before `end` (the last one of the token just read).
  long line_before(const char* end) {
    if (end > begin_) --end;
    if (end < counted_) return line_;  // the lexer never goes back; keep what is counted
    line_ += static_cast<long>(std::count(counted_, end, '\n'));
    counted_ = end;
    return line_;
  }

  // The path of a value that starts now inside the innermost container.
  std::string child_path() {
    if (stack_.empty()) return "";
    Frame& parent = stack_.back();
    if (parent.is_array) return parent.path + "[" + std::to_string(parent.next_index++) + "]";
    return parent.path.empty() ? parent.key : parent.path + "." + parent.key;
  }

  void record(const std::string& path, long at) {
    if (stack_.size() <= kRecordedDepth && !path.empty()) layout_.line_of.emplace(path, at);
  }

  void on_key(const std::string& key, long at) {
    Frame& object = stack_.back();
    object.key = key;
    const auto [it, inserted] = object.key_lines.try_emplace(object.key, at);
    if (!inserted && layout_.duplicate.empty())
      layout_.duplicate = "duplicate key " + in_quotes(object.key) +
                          (object.path.empty() ? std::string(" at the top level") : " in " + object.path) +
                          " (lines " + std::to_string(it->second) + " and " + std::to_string(at) +
                          "): a JSON object's keys must be unique (the later value would silently replace "
                          "the earlier)";
    if (!inserted && layout_.duplicate_line == 0) layout_.duplicate_line = at;
  }

  const char* begin_;
  long line_ = 1;  // the line of counted_[-1]
  const char* counted_;
  JsonLayout& layout_;
  std::vector<Frame> stack_;
};

}  // namespace

Json parse_json(const std::string& text, JsonLayout& layout) {
  const char* read = text.data();  // one past the last character the lexer has taken
  JsonLayoutRecorder recorder(text, layout);
  const Json::parser_callback_t callback = [&](int, nlohmann::json::parse_event_t event, Json& parsed) {
    recorder.on_event(event, parsed, read);
    return true;
  };
  return Json::parse(TrackedChar(text.data(), &read), TrackedChar(text.data() + text.size(), &read), callback);
}

}  // namespace panelrad::io_detail
