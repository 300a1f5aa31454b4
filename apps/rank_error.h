#pragma once
// Under mpirun every rank meets an error of the input at the same point, and main() prints it
// once, from rank 0. An error that one rank meets alone (a seed of an ensemble that failed on it)
// is thrown as RankError: every rank that has one prints it, naming itself.
#include <stdexcept>

namespace geohybrid::apps
{
class RankError : public std::runtime_error
{
public:
  using std::runtime_error::runtime_error;
};
} // namespace geohybrid::apps
