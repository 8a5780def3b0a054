#include <algorithm>

#include "relplane/eval/json_writer.hpp"
#include "relplane/eval/report_json.hpp"

namespace relplane::eval {
namespace {

void WriteVector3(JsonWriter& json, const std::string& key, const Eigen::Vector3d& v) {
  json.Key(key).Vector(v.data(), 3);
}

}  // namespace

std::map<int64_t, std::string> GroupLabels(const MapSnapshot& map) {
  std::vector<int64_t> ids;
  for (const GroupRecord& g : map.groups) ids.push_back(g.id);
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  std::map<int64_t, std::string> labels;
  for (size_t i = 0; i < ids.size(); ++i) labels[ids[i]] = "X" + std::to_string(i + 1);
  return labels;
}

std::string MapToJson(const MapSnapshot& map) {
  std::map<int64_t, std::vector<int64_t>> groups_of;  // plane id -> group ids
  for (const GroupRecord& g : map.groups) {
    for (const int64_t member : g.members) groups_of[member].push_back(g.id);
  }
  const std::map<int64_t, std::string> labels = GroupLabels(map);

  JsonWriter json;
  json.BeginObject();
  json.Field("schema", "relplane-map/1");
  json.Field("utime", map.utime).Field("seq", map.seq);
  json.Key("planes").BeginArray();
  for (const PlaneRecord& p : map.planes) {
    json.BeginObject();
    json.Field("id", p.id);
    WriteVector3(json, "normal", p.normal);
    json.Field("d", p.d);
    WriteVector3(json, "centroid", p.centroid);
    json.Key("vertices").BeginArray(true);
    for (const Eigen::Vector3d& v : p.vertices) json.Vector(v.data(), 3);
    json.EndArray();
    json.Field("observations", p.observations).Field("rms", p.rms);
    json.Key("groups").BeginArray(true);
    for (const int64_t g : groups_of[p.id]) json.Value(g);
    json.EndArray();
    json.EndObject();
  }
  json.EndArray();
  json.Key("groups").BeginArray();
  for (const GroupRecord& g : map.groups) {
    json.BeginObject();
    json.Field("id", g.id).Field("label", labels.at(g.id)).Field("basis", g.basis_id);
    json.Key("members").BeginArray(true);
    for (const int64_t m : g.members) json.Value(m);
    json.EndArray();
    json.EndObject();
  }
  json.EndArray();
  json.EndObject();
  return json.Str();
}

}  // namespace relplane::eval
