#include "snapshot_xdmf.h"

#include <cstddef>
#include <locale>
#include <sstream>

namespace geohybrid::dem::snapshot_detail
{
namespace
{
std::string xml_escape(const std::string &s)
{
  std::string out;
  for (char ch : s)
    switch (ch)
      {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default: out += ch;
      }
  return out;
}

struct XdmfGridWriter
{
  std::ostringstream &out;
  std::string file_prefix; // "name.h5:/snapshot_000000/"

  void data_item(const std::string &indent, const std::string &dims, const char *number_type, int precision,
                 const std::string &path)
  {
    out << indent << "<DataItem Dimensions=\"" << dims << "\" NumberType=\"" << number_type
        << "\" Precision=\"" << precision << "\" Format=\"HDF\">" << file_prefix << path << "</DataItem>\n";
  }
  void attribute(const char *name, const char *type, const char *centre, const std::string &dims,
                 const char *number_type, int precision, const std::string &path)
  {
    out << "          <Attribute Name=\"" << name << "\" AttributeType=\"" << type << "\" Center=\"" << centre
        << "\">\n";
    data_item("            ", dims, number_type, precision, path);
    out << "          </Attribute>\n";
  }

  void particles(std::size_t n)
  {
    const std::string ns = std::to_string(n), n3 = ns + " 3";
    out << "        <Grid Name=\"particles\" GridType=\"Uniform\">\n"
        << "          <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"" << n
        << "\" NodesPerElement=\"1\">\n";
    data_item("            ", ns, "Int", 8, "particles/connectivity");
    out << "          </Topology>\n"
        << "          <Geometry GeometryType=\"XYZ\">\n";
    data_item("            ", n3, "Float", 8, "particles/position");
    out << "          </Geometry>\n";
    attribute("radius", "Scalar", "Node", ns, "Float", 8, "particles/radius");
    attribute("velocity", "Vector", "Node", n3, "Float", 8, "particles/velocity");
    attribute("cluster_id", "Scalar", "Node", ns, "Int", 8, "particles/cluster_id");
    attribute("rotation", "Scalar", "Node", ns, "Float", 8, "particles/rotation");
    out << "        </Grid>\n";
  }

  void sheets(std::size_t n_nodes, std::size_t n_segments)
  {
    const std::string ns = std::to_string(n_nodes), ms = std::to_string(n_segments);
    out << "        <Grid Name=\"sheets\" GridType=\"Uniform\">\n"
        << "          <Topology TopologyType=\"Polyline\" NumberOfElements=\"" << n_segments
        << "\" NodesPerElement=\"2\">\n";
    data_item("            ", ms + " 2", "Int", 8, "sheets/connectivity");
    out << "          </Topology>\n"
        << "          <Geometry GeometryType=\"XYZ\">\n";
    data_item("            ", ns + " 3", "Float", 8, "sheets/position");
    out << "          </Geometry>\n";
    attribute("velocity", "Vector", "Node", ns + " 3", "Float", 8, "sheets/velocity");
    attribute("sheet_index", "Scalar", "Node", ns, "Int", 4, "sheets/sheet_index");
    attribute("tension", "Scalar", "Cell", ms, "Float", 8, "sheets/tension");
    attribute("strain", "Scalar", "Cell", ms, "Float", 8, "sheets/strain");
    out << "        </Grid>\n";
  }

  void lines(const char *name, std::size_t m, bool with_wall_index, const char *index_name = "wall_index")
  {
    const std::string ms = std::to_string(m), group = std::string(name) + "/";
    out << "        <Grid Name=\"" << name << "\" GridType=\"Uniform\">\n"
        << "          <Topology TopologyType=\"Polyline\" NumberOfElements=\"" << m << "\" NodesPerElement=\"2\">\n";
    data_item("            ", ms + " 2", "Int", 8, group + "connectivity");
    out << "          </Topology>\n"
        << "          <Geometry GeometryType=\"XYZ\">\n";
    data_item("            ", std::to_string(2 * m) + " 3", "Float", 8, group + "points");
    out << "          </Geometry>\n";
    attribute("normal_force", "Scalar", "Cell", ms, "Float", 8, group + "normal_force");
    attribute("tangential_force", "Scalar", "Cell", ms, "Float", 8, group + "tangential_force");
    attribute("force_magnitude", "Scalar", "Cell", ms, "Float", 8, group + "force_magnitude");
    attribute("bonded", "Scalar", "Cell", ms, "Int", 4, group + "bonded");
    if (with_wall_index)
      attribute(index_name, "Scalar", "Cell", ms, "Int", 4, group + "wall_index");
    out << "        </Grid>\n";
  }
};
} // namespace

std::string xdmf_entry(const std::string &h5_name, const std::string &name, double time, const SnapshotCounts &n)
{
  std::ostringstream out;
  out.imbue(std::locale::classic());
  out.precision(17);
  XdmfGridWriter grid{out, xml_escape(h5_name) + ":/" + name + "/"};
  out << "      <Grid Name=\"" << name << "\" GridType=\"Collection\" CollectionType=\"Spatial\">\n"
      << "        <Time Value=\"" << time << "\"/>\n";
  // ParaView does not read empty grids: leave them out.
  if (n.n_discs > 0)
    grid.particles(n.n_discs);
  if (n.n_contacts > 0)
    grid.lines("contacts", n.n_contacts, false);
  if (n.n_wall_contacts > 0)
    grid.lines("wall_contacts", n.n_wall_contacts, true);
  if (n.n_sheet_segments > 0)
    grid.sheets(n.n_sheet_nodes, n.n_sheet_segments);
  if (n.n_sheet_contacts > 0)
    grid.lines("sheet_contacts", n.n_sheet_contacts, true, "sheet_index");
  out << "      </Grid>\n";
  return out.str();
}
} // namespace geohybrid::dem::snapshot_detail
