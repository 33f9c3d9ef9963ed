#ifndef LME_MPM_BASE_ARCHIVE_H
#define LME_MPM_BASE_ARCHIVE_H

#include <cstdint>
#include <istream>
#include <ostream>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace lme_mpm
{
/**
 * A binary archive that either writes or reads, so that a part lists the fields it
 * saves once, in one `serialize(Archive &)`, and saving and loading cannot drift
 * apart. Trivially copyable values are stored as their bytes; vectors and strings as
 * a 64-bit length followed by their elements.
 */
class Archive
{
public:
  explicit Archive(std::ostream &out) : out(&out) {}
  explicit Archive(std::istream &in) : in(&in) {}

  bool loading() const { return in != nullptr; }
  /// False once a read or write has failed (a truncated file, a full disk).
  bool good() const { return loading() ? bool(*in) : bool(*out); }

  /// Saves or loads each argument in turn.
  template <class... T>
  void operator()(T &...values)
  {
    (io(values), ...);
  }

private:
  template <class T>
  void io(T &v)
  {
    static_assert(std::is_trivially_copyable_v<T>, "store it field by field");
    bytes(&v, sizeof(T));
  }
  template <class T>
  void io(std::vector<T> &v)
  {
    std::uint64_t n = v.size();
    io(n);
    if (loading())
      v.resize(n);
    if constexpr (std::is_trivially_copyable_v<T>)
      bytes(v.data(), n * sizeof(T));
    else
      for (auto &x : v)
        io(x);
  }
  void io(std::string &s)
  {
    std::uint64_t n = s.size();
    io(n);
    if (loading())
      s.resize(n);
    bytes(s.data(), n);
  }
  template <class A, class B>
  void io(std::pair<A, B> &p)
  {
    io(p.first);
    io(p.second);
  }
  void bytes(void *data, const std::size_t size)
  {
    if (loading())
      in->read(static_cast<char *>(data), size);
    else
      out->write(static_cast<const char *>(data), size);
  }

  std::ostream *out = nullptr;
  std::istream *in  = nullptr;
};
} // namespace lme_mpm

#endif
