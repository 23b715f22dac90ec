#include "core/flat_json.hpp"

#include <charconv>
#include <cmath>
#include <limits>

namespace slambox {

namespace {

struct Cursor {
  std::string_view s;
  std::size_t at = 0;

  void SkipSpace() {
    while (at < s.size() && (s[at] == ' ' || s[at] == '\t' || s[at] == '\r' || s[at] == '\n')) ++at;
  }
  bool Eat(char c) {
    SkipSpace();
    if (at < s.size() && s[at] == c) return ++at, true;
    return false;
  }
  bool Word(std::string_view w) {
    if (s.substr(at, w.size()) != w) return false;
    at += w.size();
    return true;
  }
  std::string Where(const std::string& what) const { return what + " at column " + std::to_string(at + 1); }
};

void AppendUtf8(unsigned code, std::string& out) {
  if (code < 0x80) {
    out += static_cast<char>(code);
  } else if (code < 0x800) {
    out += static_cast<char>(0xC0 | (code >> 6)), out += static_cast<char>(0x80 | (code & 0x3F));
  } else if (code < 0x10000) {
    out += static_cast<char>(0xE0 | (code >> 12)), out += static_cast<char>(0x80 | ((code >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (code & 0x3F));
  } else {
    out += static_cast<char>(0xF0 | (code >> 18)), out += static_cast<char>(0x80 | ((code >> 12) & 0x3F));
    out += static_cast<char>(0x80 | ((code >> 6) & 0x3F)), out += static_cast<char>(0x80 | (code & 0x3F));
  }
}

bool Hex4(Cursor& c, unsigned& code) {
  if (c.at + 4 > c.s.size()) return false;
  const auto r = std::from_chars(c.s.data() + c.at, c.s.data() + c.at + 4, code, 16);
  if (r.ptr != c.s.data() + c.at + 4) return false;
  c.at += 4;
  return true;
}

std::string String(Cursor& c, std::string& out) {
  out.clear();
  if (!c.Eat('"')) return c.Where("expected a string");
  for (;;) {
    if (c.at >= c.s.size()) return c.Where("unterminated string");
    const char ch = c.s[c.at++];
    if (ch == '"') return "";
    if (static_cast<unsigned char>(ch) < 0x20) return c.Where("control character in a string");
    if (ch != '\\') {
      out += ch;
      continue;
    }
    if (c.at >= c.s.size()) return c.Where("unterminated string");
    switch (const char e = c.s[c.at++]) {
      case '"': case '\\': case '/': out += e; break;
      case 'b': out += '\b'; break;
      case 'f': out += '\f'; break;
      case 'n': out += '\n'; break;
      case 'r': out += '\r'; break;
      case 't': out += '\t'; break;
      case 'u': {
        unsigned code = 0, low = 0;
        if (!Hex4(c, code)) return c.Where("bad \\u escape");
        if (code >= 0xD800 && code < 0xDC00) {  // a surrogate pair
          if (!c.Word("\\u") || !Hex4(c, low) || low < 0xDC00 || low >= 0xE000) return c.Where("bad surrogate pair");
          code = 0x10000 + ((code - 0xD800) << 10) + (low - 0xDC00);
        } else if (code >= 0xDC00 && code < 0xE000) {
          return c.Where("bad surrogate pair");
        }
        AppendUtf8(code, out);
        break;
      }
      default: return c.Where("bad escape");
    }
  }
}

/// A JSON number (strict grammar), or a bare NaN / Infinity / -Infinity token.
std::string Number(Cursor& c, double& value, bool& integer, bool& non_finite) {
  c.SkipSpace();
  const std::size_t start = c.at;
  if (c.Word("NaN")) return value = std::numeric_limits<double>::quiet_NaN(), non_finite = true, "";
  if (c.Word("Infinity")) return value = std::numeric_limits<double>::infinity(), non_finite = true, "";
  if (c.Word("-Infinity")) return value = -std::numeric_limits<double>::infinity(), non_finite = true, "";
  const auto digit = [&] { return c.at < c.s.size() && c.s[c.at] >= '0' && c.s[c.at] <= '9'; };
  const auto digits = [&] {
    const std::size_t from = c.at;
    while (digit()) ++c.at;
    return c.at > from;
  };
  if (c.at < c.s.size() && c.s[c.at] == '-') ++c.at;
  if (c.at < c.s.size() && c.s[c.at] == '0') ++c.at;
  else if (!digits()) return c.Where("expected a number");
  integer = true;
  if (c.at < c.s.size() && c.s[c.at] == '.') {
    ++c.at, integer = false;
    if (!digits()) return c.Where("expected digits after '.'");
  }
  if (c.at < c.s.size() && (c.s[c.at] == 'e' || c.s[c.at] == 'E')) {
    ++c.at, integer = false;
    if (c.at < c.s.size() && (c.s[c.at] == '+' || c.s[c.at] == '-')) ++c.at;
    if (!digits()) return c.Where("expected digits in the exponent");
  }
  const auto r = std::from_chars(c.s.data() + start, c.s.data() + c.at, value);
  if (r.ec == std::errc::result_out_of_range) return c.Where("number out of range");
  if (r.ptr != c.s.data() + c.at) return c.Where("bad number");
  return "";
}

std::string Value(Cursor& c, FlatValue& v) {
  c.SkipSpace();
  if (c.at >= c.s.size()) return c.Where("expected a value");
  const char ch = c.s[c.at];
  if (ch == '"') return v.kind = FlatValue::Kind::kString, String(c, v.text);
  if (c.Word("true")) return v.kind = FlatValue::Kind::kBool, v.boolean = true, "";
  if (c.Word("false")) return v.kind = FlatValue::Kind::kBool, v.boolean = false, "";
  if (c.Word("null")) return v.kind = FlatValue::Kind::kNull, "";
  if (ch == '[') {
    ++c.at;
    v.kind = FlatValue::Kind::kNumberArray;
    if (c.Eat(']')) return "";
    do {
      double x = 0.0;
      bool integer = false;
      if (std::string e = Number(c, x, integer, v.non_finite); !e.empty()) return e + " (arrays hold numbers only)";
      v.numbers.push_back(x);
    } while (c.Eat(','));
    return c.Eat(']') ? "" : c.Where("expected ',' or ']'");
  }
  if (ch == '{') return c.Where("nested objects are not part of any answer");
  v.kind = FlatValue::Kind::kNumber;
  return Number(c, v.number, v.integer, v.non_finite);
}

}  // namespace

std::string ParseFlatObject(std::string_view line, FlatObject& out) {
  out.members.clear();
  Cursor c{line};
  if (!c.Eat('{')) return c.Where("expected '{'");
  if (!c.Eat('}')) {
    do {
      std::string key;
      if (std::string e = String(c, key); !e.empty()) return e;
      if (out.Find(key)) return c.Where("duplicate key '" + key + "'");
      if (!c.Eat(':')) return c.Where("expected ':'");
      FlatValue v;
      if (std::string e = Value(c, v); !e.empty()) return e;
      out.members.emplace_back(std::move(key), std::move(v));
    } while (c.Eat(','));
    if (!c.Eat('}')) return c.Where("expected ',' or '}'");
  }
  c.SkipSpace();
  return c.at == line.size() ? "" : c.Where("text after the object");
}

}  // namespace slambox
