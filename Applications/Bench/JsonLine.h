// SPDX-License-Identifier: BSD-3-Clause
// JsonLine: the one-line JSON object that anisovoronoi-bench prints per case.
#ifndef avbench_JsonLine_h
#define avbench_JsonLine_h

#include <cmath>
#include <cstddef>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

namespace avbench
{

/// Ordered key/value pairs printed as one JSON object on one line (non-finite numbers -> null).
class JsonLine
{
public:
  void Set(const std::string& key, const std::string& value)
  {
    std::string esc = "\"";
    for (char c : value)
    {
      if (c == '"' || c == '\\')
      {
        esc += '\\';
      }
      esc += c;
    }
    this->Put(key, esc + "\"");
  }
  void Set(const std::string& key, const char* value) { this->Set(key, std::string(value)); }
  void Set(const std::string& key, double value)
  {
    if (!std::isfinite(value))
    {
      this->Put(key, "null");
      return;
    }
    char buf[64];
    std::snprintf(buf, sizeof(buf), "%.6g", value);
    this->Put(key, buf);
  }
  void Set(const std::string& key, long long value) { this->Put(key, std::to_string(value)); }
  void Set(const std::string& key, int value) { this->Put(key, std::to_string(value)); }
  void Set(const std::string& key, std::size_t value) { this->Put(key, std::to_string(value)); }
  void Set(const std::string& key, bool value) { this->Put(key, value ? "true" : "false"); }
  void Set(const std::string& key, const std::vector<std::size_t>& values)
  {
    std::string s = "[";
    for (std::size_t i = 0; i < values.size(); ++i)
      s += (i ? ", " : "") + std::to_string(values[i]);
    this->Put(key, s + "]");
  }
  std::string Str() const
  {
    std::string s = "{";
    for (std::size_t i = 0; i < this->Items.size(); ++i)
    {
      s += (i ? ", \"" : "\"") + this->Items[i].first + "\": " + this->Items[i].second;
    }
    return s + "}";
  }

private:
  void Put(const std::string& key, const std::string& raw)
  {
    for (auto& kv : this->Items)
    {
      if (kv.first == key)
      {
        kv.second = raw;
        return;
      }
    }
    this->Items.emplace_back(key, raw);
  }
  std::vector<std::pair<std::string, std::string>> Items;
};

} // namespace avbench

#endif
