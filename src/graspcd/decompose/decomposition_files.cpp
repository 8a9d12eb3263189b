// The OBJ pieces and the MJCF fragment of a decomposition (decomposition_files.h).
#include "graspcd/decompose/decomposition_files.h"

#include <tinyxml2.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <stdexcept>
#include <string>

namespace graspcd::decompose {

namespace {

void write_obj(const std::filesystem::path& path, const TriangleMesh& mesh,
               const std::string& comment, const std::filesystem::path& named) {
  std::ofstream out(path, std::ios::binary);
  out << "# " << comment << '\n' << std::setprecision(17);
  for (const Vec3& v : mesh.vertices) out << "v " << v.x() << ' ' << v.y() << ' ' << v.z() << '\n';
  for (const auto& f : mesh.faces) {
    out << "f " << f[0] + 1 << ' ' << f[1] + 1 << ' ' << f[2] + 1 << '\n';
  }
  out.flush();
  if (!out) throw std::runtime_error(named.string() + ": cannot write the piece");
}

// XML forbids "--" inside a comment.
std::string comment_text(std::string text) {
  for (std::size_t at = text.find("--"); at != std::string::npos; at = text.find("--", at)) {
    text.replace(at, 2, "- -");
  }
  return ' ' + text + ' ';
}

}  // namespace

DecompositionFiles write_decomposition_files(const std::vector<ConvexPiece>& pieces,
                                             const std::string& dir, const std::string& stem,
                                             const std::string& comment, const std::string& named) {
  const std::filesystem::path folder(dir);
  const std::filesystem::path shown(named.empty() ? dir : named);
  DecompositionFiles files;
  files.fragment = stem + ".xml";
  tinyxml2::XMLDocument doc;
  doc.InsertEndChild(doc.NewComment(comment_text(comment).c_str()));
  tinyxml2::XMLElement* root = doc.NewElement("mujocoinclude");
  doc.InsertEndChild(root);
  tinyxml2::XMLElement* asset = root->InsertNewChildElement("asset");
  tinyxml2::XMLElement* body =
      root->InsertNewChildElement("worldbody")->InsertNewChildElement("body");
  body->SetAttribute("name", stem.c_str());
  for (std::size_t k = 0; k < pieces.size(); ++k) {
    const std::string name = stem + "_piece_" + std::to_string(k);
    const std::string file = name + ".obj";
    write_obj(folder / file, pieces[k].hull,
              "graspcd decompose: convex piece " + std::to_string(k) + " of " + stem, shown / file);
    files.pieces.push_back(file);
    tinyxml2::XMLElement* mesh = asset->InsertNewChildElement("mesh");
    mesh->SetAttribute("name", name.c_str());
    mesh->SetAttribute("file", file.c_str());
    tinyxml2::XMLElement* geom = body->InsertNewChildElement("geom");
    geom->SetAttribute("name", name.c_str());
    geom->SetAttribute("type", "mesh");
    geom->SetAttribute("mesh", name.c_str());
  }
  const std::string fragment = (folder / files.fragment).string();
  if (doc.SaveFile(fragment.c_str()) != tinyxml2::XML_SUCCESS) {
    throw std::runtime_error((shown / files.fragment).string() +
                             ": cannot write the MJCF fragment");
  }
  return files;
}

}  // namespace graspcd::decompose
