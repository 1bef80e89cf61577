#include "json_node.h"

#include <set>
#include <sstream>

namespace physhand::syntax {

std::string str(double v) {
    std::ostringstream out;
    out << v;
    return out.str();
}

std::string in_quotes(std::string_view s) {
    return '"' + std::string(s) + '"';
}

std::string key_path(const std::string& path, std::string_view key) {
    return path.empty() ? std::string(key) : path + '.' + std::string(key);
}

std::string index_path(const std::string& path, std::size_t i) {
    return path + '[' + std::to_string(i) + ']';
}

[[noreturn]] void fail_at(const std::string& path, std::string_view what) {
    throw FormatError(path.empty() ? std::string(what) : path + ": " + std::string(what));
}

namespace {

// nlohmann::json keeps the last of duplicate keys; in a scene file they are an error.
// Tracks the path of the value being parsed, for the message.
class DuplicateKeyCheck {
  public:
    bool operator()(int /*depth*/, json::parse_event_t event, json& parsed) {
        using Event = json::parse_event_t;
        switch (event) {
            case Event::object_start:
            case Event::array_start:
                frames_.emplace_back();
                frames_.back().array = event == Event::array_start;
                break;
            case Event::key: {
                Frame& frame = frames_.back();
                frame.key = parsed.get<std::string>();
                if (!frame.keys.insert(frame.key).second) fail_at(path(), "duplicate key");
                break;
            }
            case Event::object_end:
            case Event::array_end:
                frames_.pop_back();
                [[fallthrough]];
            case Event::value:
                if (!frames_.empty() && frames_.back().array) ++frames_.back().index;
                break;
        }
        return true;
    }

  private:
    struct Frame {
        bool array = false;
        std::size_t index = 0;
        std::string key;
        std::set<std::string> keys;
    };

    std::string path() const {
        std::string path;
        for (const Frame& frame : frames_) {
            path = frame.array ? index_path(path, frame.index) : key_path(path, frame.key);
        }
        return path;
    }

    std::vector<Frame> frames_;
};

}  // namespace

double read_time_after(const Object& entry, std::optional<double> previous) {
    const Node node = entry.at("t");
    const double t = node.number();
    if (previous && !(t > *previous)) {
        node.fail("expected a time after the previous entry's (" + str(*previous) + ")");
    }
    return t;
}

// `to_s` after `from_s`.
std::pair<double, double> read_interval(const Object& obj) {
    const double from = obj.at("from_s").number();
    const Node to_node = obj.at("to_s");
    const double to = to_node.number();
    if (!(to > from)) to_node.fail("expected a time after from_s (" + str(from) + ")");
    return {from, to};
}

json parse_json(const std::string& text) {
    try {
        return json::parse(text, DuplicateKeyCheck());
    } catch (const json::exception& e) {
        // Drop nlohmann's "[json.exception.parse_error.101] " tag; keep line and column.
        const std::string_view what = e.what();
        const std::size_t tag_end = what.find("] ");
        throw FormatError("invalid JSON: " + std::string(tag_end == std::string_view::npos
                                                             ? what
                                                             : what.substr(tag_end + 2)));
    }
}

}  // namespace physhand::syntax
