#include "graspcd/mujoco/model_check.h"

#include <mujoco/mjxmacro.h>

#include <cmath>
#include <cstring>
#include <sstream>
#include <type_traits>

namespace graspcd::mujoco {
namespace {

// The object type of an array's rows, by the name of its row count in MJMODEL_POINTERS.
int object_type(const char* rows) {
  static const struct {
    const char* rows;
    int type;
  } kTypes[] = {{"nbody", mjOBJ_BODY},       {"njnt", mjOBJ_JOINT},   {"ngeom", mjOBJ_GEOM},
                {"nsite", mjOBJ_SITE},       {"ncam", mjOBJ_CAMERA},  {"nlight", mjOBJ_LIGHT},
                {"nmesh", mjOBJ_MESH},       {"nskin", mjOBJ_SKIN},   {"nhfield", mjOBJ_HFIELD},
                {"nmat", mjOBJ_MATERIAL},    {"npair", mjOBJ_PAIR},   {"neq", mjOBJ_EQUALITY},
                {"ntendon", mjOBJ_TENDON},   {"nu", mjOBJ_ACTUATOR},  {"nsensor", mjOBJ_SENSOR},
                {"nnumeric", mjOBJ_NUMERIC}, {"ntuple", mjOBJ_TUPLE}, {"nkey", mjOBJ_KEY}};
  for (const auto& t : kTypes) {
    if (std::strcmp(t.rows, rows) == 0) return t.type;
  }
  return mjOBJ_UNKNOWN;
}

// "geom 5 'object'", "mesh 0 'cup' (vertex 12)" or "row 7" for a row of an array.
std::string row_label(const mjModel* m, const char* rows, int row) {
  std::ostringstream out;
  int type = object_type(rows);
  int id = row;
  if (std::strcmp(rows, "nmeshvert") == 0) {
    type = mjOBJ_MESH;
    for (id = m->nmesh - 1; id > 0 && m->mesh_vertadr[id] > row; --id) {
    }
  }
  if (type == mjOBJ_UNKNOWN) {
    out << "row " << row;
    return out.str();
  }
  const char* name = mj_id2name(m, type, id);
  out << mju_type2Str(type) << ' ' << id;
  if (name != nullptr && *name != '\0') out << " '" << name << '\'';
  if (std::strcmp(rows, "nmeshvert") == 0) out << " (vertex " << row - m->mesh_vertadr[id] << ')';
  return out.str();
}

template <class T>
bool check_array(const mjModel* m, const T* values, int rows, int columns, const char* array,
                 const char* row_name, std::string& found) {
  if constexpr (std::is_floating_point_v<T>) {
    if (!found.empty() || values == nullptr) return found.empty();
    for (long i = 0; i < static_cast<long>(rows) * columns; ++i) {
      if (std::isfinite(values[i])) continue;
      std::ostringstream out;
      out << "the model holds a non-finite number: " << array << " of "
          << row_label(m, row_name, static_cast<int>(i / columns)) << " is " << values[i];
      found = out.str();
      return false;
    }
  } else {
    (void)m, (void)values, (void)rows, (void)columns, (void)array, (void)row_name;
  }
  return found.empty();
}

}  // namespace

std::string find_non_finite(const mjModel* m) {
  std::string found;
  const mjOption& o = m->opt;
  const mjtNum options[] = {
      o.timestep,    o.apirate,     o.impratio,    o.tolerance, o.noslip_tolerance, o.mpr_tolerance,
      o.gravity[0],  o.gravity[1],  o.gravity[2],  o.wind[0],   o.wind[1],          o.wind[2],
      o.magnetic[0], o.magnetic[1], o.magnetic[2], o.density,   o.viscosity,        o.o_margin};
  for (const mjtNum x : options) {
    if (!std::isfinite(x)) return "the model holds a non-finite number in its <option>";
  }
  // Every array of mjModel (mjxmacro.h): X(type, name, rows, columns), columns sometimes a size
  // of the model (MJ_M).
#undef MJ_M
#define MJ_M(n) m->n
#define X(type, name, rows, columns) \
  check_array(m, m->name, m->rows, static_cast<int>(columns), #name, #rows, found);
  MJMODEL_POINTERS
#undef X
#undef MJ_M
#define MJ_M(n) n
  return found;
}

}  // namespace graspcd::mujoco
