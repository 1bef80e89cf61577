#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "format_error.h"
#include "pose.h"

// Reading the project's JSON files (scene files, the layer's config) with messages that name
// the JSON path of what is wrong and what was expected.
namespace physhand::syntax {

using json = nlohmann::json;
using Keys = std::span<const std::string_view>;

std::string str(double v);
std::string in_quotes(std::string_view s);
std::string key_path(const std::string& path, std::string_view key);
std::string index_path(const std::string& path, std::size_t i);
[[noreturn]] void fail_at(const std::string& path, std::string_view what);

// "a, b or c"
template <class Table>
std::string names_of(const Table& table) {
    std::string names;
    for (std::size_t i = 0; i < table.size(); ++i) {
        if (i > 0) names += i + 1 == table.size() ? " or " : ", ";
        names += table[i].name;
    }
    return names;
}

// A JSON value and its path in the scene file; every check fails with that path.
class Node {
  public:
    Node(const json& value, std::string path) : value_(&value), path_(std::move(path)) {}

    const json& value() const { return *value_; }
    const std::string& path() const { return path_; }
    [[noreturn]] void fail(std::string_view what) const { fail_at(path_, what); }

    double number() const {
        if (!value_->is_number()) fail("expected a number");
        const double v = value_->get<double>();
        if (!std::isfinite(v)) fail("expected a finite number");
        return v;
    }
    double positive() const {
        const double v = number();
        if (!(v > 0)) fail("expected a number > 0");
        return v;
    }
    double non_negative() const {
        const double v = number();
        if (!(v >= 0)) fail("expected a number >= 0");
        return v;
    }
    double in_range(double lo, double hi) const {
        const double v = number();
        if (!(v >= lo && v <= hi)) fail("expected a number in [" + str(lo) + ", " + str(hi) + "]");
        return v;
    }
    std::uint64_t unsigned_integer() const {
        if (!value_->is_number_unsigned()) fail("expected a non-negative integer");
        return value_->get<std::uint64_t>();
    }
    // An index into a list of `count` items.
    int index(std::size_t count) const {
        if (!value_->is_number_integer() || value_->get<std::int64_t>() < 0 ||
            value_->get<std::uint64_t>() >= count) {
            fail("expected an integer index in [0, " + std::to_string(count - 1) + "]");
        }
        return value_->get<int>();
    }
    std::string string() const {
        if (!value_->is_string()) fail("expected a string");
        return value_->get<std::string>();
    }
    std::string non_empty_string() const {
        std::string s = string();
        if (s.empty()) fail("expected a non-empty string");
        return s;
    }

    std::vector<Node> array(std::size_t min_size = 0,
                            std::string_view what = "expected an array") const {
        if (!value_->is_array() || value_->size() < min_size) fail(what);
        std::vector<Node> items;
        for (std::size_t i = 0; i < value_->size(); ++i) {
            items.emplace_back((*value_)[i], index_path(path_, i));
        }
        return items;
    }
    // Exactly `n` numbers, returned as nodes so that each can be range-checked at its path.
    std::vector<Node> numbers(std::size_t n) const {
        const std::string what = "expected an array of " + std::to_string(n) + " numbers";
        std::vector<Node> items = array(n, what);
        if (items.size() != n || !std::all_of(items.begin(), items.end(), [](const Node& e) {
                return e.value().is_number();
            })) {
            fail(what);
        }
        return items;
    }
    Vec3 vec3() const {
        const auto e = numbers(3);
        return {e[0].number(), e[1].number(), e[2].number()};
    }

    // The entry of `table` (entries with a `name`) that this string names.
    template <class Table>
    const auto& choice(const Table& table, std::string_view noun) const {
        const std::string s = string();
        for (const auto& entry : table) {
            if (entry.name == s) return entry;
        }
        fail("unknown " + std::string(noun) + ' ' + in_quotes(s) + " (expected " + names_of(table) +
             ')');
    }

  private:
    const json* value_;
    std::string path_;
};

class Object {
  public:
    explicit Object(Node node) : node_(std::move(node)) {
        if (!node_.value().is_object()) node_.fail("expected an object");
    }

    // Every key must be one of `keys` or `more`.
    void allow(Keys keys, Keys more = {}) const {
        for (const auto& item : node_.value().items()) {
            const auto known = [&](Keys list) {
                return std::find(list.begin(), list.end(), item.key()) != list.end();
            };
            if (!known(keys) && !known(more)) fail_at(path_of(item.key()), "unknown key");
        }
    }
    std::optional<Node> find(std::string_view key) const {
        const auto it = node_.value().find(key);
        if (it == node_.value().end()) return std::nullopt;
        return Node(*it, path_of(key));
    }
    Node at(std::string_view key) const {
        auto node = find(key);
        if (!node) fail_at(path_of(key), "required");
        return *node;
    }
    void forbid(std::string_view key, std::string_view why) const {
        if (const auto node = find(key)) node->fail(why);
    }
    // `read` (a function of a Node) applied to the key's value, or `fallback` when absent.
    template <class Read, class T>
    T get_or(std::string_view key, Read read, T fallback) const {
        const auto node = find(key);
        return node ? T(std::invoke(read, *node)) : fallback;
    }
    std::string path_of(std::string_view key) const { return key_path(node_.path(), key); }

  private:
    Node node_;
};

template <class T>
struct Named {
    std::string_view name;
    T value;
};

// The last entry's time, for lists that must be strictly increasing in time.
template <class List>
std::optional<double> last_time(const List& list) {
    return list.empty() ? std::nullopt : std::optional(list.back().t);
}

// An entry's "t", after `previous`.
double read_time_after(const Object& entry, std::optional<double> previous);
// `to_s` after `from_s`.
std::pair<double, double> read_interval(const Object& obj);

// Parsed JSON text; duplicate keys, which nlohmann::json would silently collapse, are an error.
json parse_json(const std::string& text);

}  // namespace physhand::syntax
