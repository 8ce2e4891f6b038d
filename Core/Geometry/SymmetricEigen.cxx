#include "Geometry/SymmetricEigen.h"

#include <cmath>

namespace fiberpli
{

void symmetricEigen3(const double m[3][3], double values[3], Vec3 vectors[3], double relativeStop)
{
  double a[3][3], v[3][3] = { { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 } };
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      a[r][c] = m[r][c];
    }
  }
  for (int sweep = 0; sweep < 50; ++sweep)
  {
    const double off = a[0][1] * a[0][1] + a[0][2] * a[0][2] + a[1][2] * a[1][2];
    if (off == 0.0 ||
      off <= relativeStop * (a[0][0] * a[0][0] + a[1][1] * a[1][1] + a[2][2] * a[2][2]))
    {
      break;
    }
    for (int p = 0; p < 2; ++p)
    {
      for (int q = p + 1; q < 3; ++q)
      {
        if (a[p][q] == 0.0)
        {
          continue;
        }
        // Rotation that zeroes a[p][q] (Golub & Van Loan, symmetric Schur 2×2).
        const double theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
        const double t =
          (theta >= 0 ? 1.0 : -1.0) / (std::abs(theta) + std::sqrt(theta * theta + 1.0));
        const double c = 1.0 / std::sqrt(t * t + 1.0), s = t * c;
        for (int k = 0; k < 3; ++k)
        {
          const double akp = a[k][p], akq = a[k][q];
          a[k][p] = c * akp - s * akq;
          a[k][q] = s * akp + c * akq;
        }
        for (int k = 0; k < 3; ++k)
        {
          const double apk = a[p][k], aqk = a[q][k];
          a[p][k] = c * apk - s * aqk;
          a[q][k] = s * apk + c * aqk;
        }
        for (int k = 0; k < 3; ++k)
        {
          const double vkp = v[k][p], vkq = v[k][q];
          v[k][p] = c * vkp - s * vkq;
          v[k][q] = s * vkp + c * vkq;
        }
      }
    }
  }
  int order[3] = { 0, 1, 2 };
  for (int i = 0; i < 3; ++i)
  {
    for (int j = i + 1; j < 3; ++j)
    {
      if (a[order[j]][order[j]] > a[order[i]][order[i]])
      {
        const int t = order[i];
        order[i] = order[j];
        order[j] = t;
      }
    }
  }
  for (int k = 0; k < 3; ++k)
  {
    values[k] = a[order[k]][order[k]];
    vectors[k] = normalized(Vec3{ v[0][order[k]], v[1][order[k]], v[2][order[k]] });
  }
}

} // namespace fiberpli
