// SPDX-License-Identifier: BSD-3-Clause
#include "OffReader.h"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <vector>

namespace av
{
namespace
{
/// Splits the text into whitespace tokens that remember their line; '#' starts a comment.
struct Tokens
{
  std::vector<std::pair<std::string, std::size_t>> Items;
  std::size_t Next = 0;
  std::string Source;

  [[noreturn]] void Fail(std::size_t line, const std::string& what) const
  {
    std::ostringstream os;
    os << Source << ":" << line << ": " << what;
    throw InputError(os.str());
  }
  std::size_t Line() const
  {
    return Next < Items.size() ? Items[Next].second
                               : (Items.empty() ? 1 : Items.back().second);
  }
  const std::string& Take(const char* expected)
  {
    if (Next >= Items.size())
      Fail(Line(), std::string("file ends where ") + expected + " was expected (truncated?)");
    return Items[Next++].first;
  }
  long long Integer(const char* expected)
  {
    const std::size_t line = Line();
    const std::string& t = Take(expected);
    char* end = nullptr;
    const long long v = std::strtoll(t.c_str(), &end, 10);
    if (!end || *end)
      Fail(line, std::string("expected ") + expected + ", got '" + t + "'");
    return v;
  }
  double Real(const char* expected)
  {
    const std::size_t line = Line();
    const std::string& t = Take(expected);
    char* end = nullptr;
    const double v = std::strtod(t.c_str(), &end);
    if (!end || *end || !std::isfinite(v))
      Fail(line, std::string("expected a finite ") + expected + ", got '" + t + "'");
    return v;
  }
};
}

SimplexMesh ParseOff(const std::string& text, const std::string& sourceName)
{
  Tokens tokens;
  tokens.Source = sourceName;
  std::istringstream lines(text);
  std::string line;
  std::size_t number = 0;
  // Face lines may carry colors after the indices: keep line boundaries for faces.
  std::vector<std::vector<std::string>> byLine;
  while (std::getline(lines, line))
  {
    ++number;
    const std::size_t hash = line.find('#');
    if (hash != std::string::npos)
      line.erase(hash);
    std::istringstream words(line);
    std::string w;
    while (words >> w)
      tokens.Items.emplace_back(w, number);
  }
  if (tokens.Items.empty() || tokens.Items[0].first.size() < 3 ||
    tokens.Items[0].first.compare(tokens.Items[0].first.size() - 3, 3, "OFF") != 0)
    tokens.Fail(1, "not an OFF file (the first word must be OFF)");
  if (tokens.Items[0].first != "OFF")
    tokens.Fail(1, "only plain ASCII 'OFF' is supported, not '" + tokens.Items[0].first + "'");
  tokens.Next = 1;
  const long long nv = tokens.Integer("the number of vertices");
  const long long nf = tokens.Integer("the number of faces");
  tokens.Integer("the number of edges");
  const std::size_t left = tokens.Items.size() - tokens.Next;
  // Divide rather than multiply: a count near 2^63 / 3 must not wrap around to a small product.
  if (nv < 3 || nf < 1 || static_cast<unsigned long long>(nv) > left / 3 ||
    static_cast<unsigned long long>(nf) > left / 4)
    tokens.Fail(tokens.Line(), "the counts (" + std::to_string(nv) + " vertices, " +
        std::to_string(nf) + " faces) do not fit in the file (truncated?)");

  SimplexMesh mesh;
  mesh.AmbientDim = 3;
  mesh.SimplexDim = 2;
  mesh.Points.reserve(static_cast<std::size_t>(nv) * 3);
  for (long long i = 0; i < nv * 3; ++i)
    mesh.Points.push_back(tokens.Real("vertex coordinate"));
  for (long long f = 0; f < nf; ++f)
  {
    const std::size_t faceLine = tokens.Line();
    const long long n = tokens.Integer("the vertex count of a face");
    if (n < 3 || n > 1000000)
      tokens.Fail(faceLine, "a face needs at least 3 vertices, got " + std::to_string(n));
    std::vector<std::int32_t> ids(static_cast<std::size_t>(n));
    for (long long k = 0; k < n; ++k)
    {
      const long long id = tokens.Integer("a vertex index");
      if (id < 0 || id >= nv)
        tokens.Fail(faceLine, "vertex index " + std::to_string(id) + " is outside [0, " +
            std::to_string(nv) + ")");
      ids[static_cast<std::size_t>(k)] = static_cast<std::int32_t>(id);
    }
    // Optional color values up to the end of the face's line.
    while (tokens.Next < tokens.Items.size() && tokens.Items[tokens.Next].second == faceLine)
      ++tokens.Next;
    for (std::size_t k = 1; k + 1 < ids.size(); ++k)
    {
      mesh.Cells.push_back(ids[0]);
      mesh.Cells.push_back(ids[k]);
      mesh.Cells.push_back(ids[k + 1]);
    }
  }
  return mesh;
}

SimplexMesh ReadOff(const std::string& fileName)
{
  std::ifstream in(fileName, std::ios::binary);
  if (!in)
    throw InputError("cannot open '" + fileName + "'");
  std::ostringstream text;
  text << in.rdbuf();
  return ParseOff(text.str(), fileName);
}
}
