#pragma once
// One way to refuse bad material input: an std::invalid_argument naming where the parameter comes
// from, the parameter, its value and the admissible range with the unit.
#include <sstream>
#include <stdexcept>
#include <string>

namespace geohybrid::fem
{
inline void require_parameter(bool condition, const std::string &where, const std::string &name,
                              double value, const std::string &admissible)
{
  if (!condition)
    {
      std::ostringstream message;
      message << where << ": parameter '" << name << "' = " << value << " " << admissible;
      throw std::invalid_argument(message.str());
    }
}
} // namespace geohybrid::fem
