#include "common/dds/entity.hpp"

#include <algorithm>
#include <cstring>
#include <memory>
#include <optional>
#include <string_view>

namespace wsn::dds {
namespace {

constexpr char kRoleMarker[] = "wsntrack-role";

void markOwner(Qos& q, Endpoint owner) {
  if (owner == Endpoint::kRole) dds_qset_userdata(q.get(), kRoleMarker, sizeof kRoleMarker - 1);
}

/// An endpoint's user data, or nothing.
std::optional<std::string> userData(const dds_qos_t* qos) {
  void* data = nullptr;
  std::size_t size = 0;
  if (qos == nullptr || !dds_qget_userdata(qos, &data, &size)) return std::nullopt;
  std::string out(static_cast<const char*>(data), size);
  dds_free(data);
  return out;
}

/// The marker alone, or followed by a space and the owner's identity.
bool isRoleData(std::string_view data) {
  const std::string_view marker(kRoleMarker, sizeof kRoleMarker - 1);
  return data.starts_with(marker) && (data.size() == marker.size() || data[marker.size()] == ' ');
}

bool isRoleEndpoint(const dds_qos_t* qos) {
  const auto data = userData(qos);
  return data && isRoleData(*data);
}

/// The user data of the endpoints of the role process named `identity`.
std::string ownerData(const std::string& identity) { return std::string(kRoleMarker) + " " + identity; }

/// `qos` with the participant's identity after the role marker, for a role endpoint of a
/// participant that has one; otherwise nothing (use `qos` as it is).
std::optional<Qos> withIdentity(const Participant& participant, const Qos& qos) {
  if (participant.identity().empty() || !isRoleEndpoint(qos.get())) return std::nullopt;
  Qos copy;
  check(dds_copy_qos(copy.get(), qos.get()), "dds_copy_qos");
  const std::string data = ownerData(participant.identity());
  dds_qset_userdata(copy.get(), data.data(), data.size());
  return copy;
}

/// The handles of the endpoints matched by `entity`, from `list` (dds_get_matched_subscriptions
/// or dds_get_matched_publications).
std::vector<dds_instance_handle_t> matchedHandles(dds_entity_t entity,
                                                  dds_return_t (*list)(dds_entity_t, dds_instance_handle_t*, size_t),
                                                  const char* what) {
  std::vector<dds_instance_handle_t> handles(16);
  while (true) {
    const auto n = static_cast<std::size_t>(check(list(entity, handles.data(), handles.size()), what));
    if (n <= handles.size()) {
      handles.resize(n);
      return handles;
    }
    handles.resize(n);
  }
}

using EndpointData = std::unique_ptr<dds_builtintopic_endpoint_t, void (*)(dds_builtintopic_endpoint_t*)>;

EndpointData endpointData(dds_builtintopic_endpoint_t* data) {
  // Null when the endpoint unmatched since the list was taken: it no longer counts.
  return {data, [](dds_builtintopic_endpoint_t* e) {
            if (e != nullptr) dds_builtintopic_free_endpoint(e);
          }};
}

}  // namespace

dds_return_t check(dds_return_t rc, const std::string& what) {
  if (rc < 0) throw DdsError(what + " failed: " + dds_strretcode(rc));
  return rc;
}

Qos Qos::reliableKeepAll(Endpoint owner) {
  Qos q;
  markOwner(q, owner);
  dds_qset_reliability(q.get(), DDS_RELIABILITY_RELIABLE, DDS_SECS(30));
  dds_qset_history(q.get(), DDS_HISTORY_KEEP_ALL, 0);
  dds_qset_durability(q.get(), DDS_DURABILITY_VOLATILE);
  return q;
}

Qos&& Qos::inPartition(const std::string& name) && {
  dds_qset_partition1(qos_, name.c_str());
  return std::move(*this);
}

Qos&& Qos::keepingAll() && {
  dds_qset_history(qos_, DDS_HISTORY_KEEP_ALL, 0);
  return std::move(*this);
}

Qos&& Qos::inPartitions(const std::vector<std::string>& names) && {
  std::vector<const char*> pointers;
  for (const auto& name : names) pointers.push_back(name.c_str());
  dds_qset_partition(qos_, static_cast<std::uint32_t>(pointers.size()), pointers.data());
  return std::move(*this);
}

Qos Qos::bestEffort(Endpoint owner) {
  Qos q;
  markOwner(q, owner);
  dds_qset_reliability(q.get(), DDS_RELIABILITY_BEST_EFFORT, 0);
  dds_qset_history(q.get(), DDS_HISTORY_KEEP_ALL, 0);
  dds_qset_durability(q.get(), DDS_DURABILITY_VOLATILE);
  return q;
}

Qos Qos::lastValueTransientLocal(Endpoint owner) {
  Qos q;
  markOwner(q, owner);
  dds_qset_reliability(q.get(), DDS_RELIABILITY_RELIABLE, DDS_SECS(30));
  dds_qset_history(q.get(), DDS_HISTORY_KEEP_LAST, 1);
  dds_qset_durability(q.get(), DDS_DURABILITY_TRANSIENT_LOCAL);
  return q;
}

Domain::Domain(dds_domainid_t id, const std::string& config_xml)
    : Entity(check(dds_create_domain(id, config_xml.c_str()), "dds_create_domain " + std::to_string(id))), id_(id) {}

Participant::Participant(dds_domainid_t domain, std::string identity)
    : Entity(check(dds_create_participant(domain, nullptr, nullptr), "dds_create_participant")),
      identity_(std::move(identity)) {}

Participant::Participant(const Participant& shared, std::string identity)
    : Entity(shared.handle()), identity_(std::move(identity)), owned_(false) {}

dds_entity_t createTopic(const Participant& participant, const dds_topic_descriptor_t& descriptor,
                         std::size_t sample_size, const std::string& name) {
  if (descriptor.m_size != sample_size)
    throw DdsError("dds_create_topic " + name + ": descriptor " + descriptor.m_typename + " is for samples of " +
                   std::to_string(descriptor.m_size) + " bytes, the bound type has " + std::to_string(sample_size));
  return check(dds_create_topic(participant.handle(), &descriptor, name.c_str(), nullptr, nullptr),
               "dds_create_topic " + name);
}

WriterBase::WriterBase(const Participant& participant, dds_entity_t topic, const Qos& qos)
    : Entity([&] {
        const auto own = withIdentity(participant, qos);
        return check(dds_create_writer(participant.handle(), topic, own ? own->get() : qos.get(), nullptr),
                     "dds_create_writer");
      }()) {
  check(dds_set_status_mask(handle(), DDS_PUBLICATION_MATCHED_STATUS), "dds_set_status_mask(writer)");
}

std::int32_t WriterBase::matchedReaders() const {
  dds_publication_matched_status_t status;
  check(dds_get_publication_matched_status(handle(), &status), "dds_get_publication_matched_status");
  return static_cast<std::int32_t>(status.current_count);
}

std::vector<const std::string*> WriterBase::matchedReaderData() const {
  std::vector<const std::string*> out;
  for (const auto reader : matchedHandles(handle(), dds_get_matched_subscriptions, "dds_get_matched_subscriptions")) {
    auto known = reader_data_.find(reader);
    if (known == reader_data_.end()) {
      const auto data = endpointData(dds_get_matched_subscription_data(handle(), reader));
      if (!data) continue;  // unmatched since the list was taken: neither counted nor remembered
      known = reader_data_.emplace(reader, userData(data->qos).value_or("")).first;
    }
    out.push_back(&known->second);
  }
  return out;
}

std::int32_t WriterBase::matchedRoleReaders() const {
  const auto readers = matchedReaderData();
  return static_cast<std::int32_t>(std::count_if(readers.begin(), readers.end(), [](const std::string* d) { return isRoleData(*d); }));
}

bool WriterBase::matchesReaderOf(const std::string& identity) const {
  const auto readers = matchedReaderData();
  const std::string owner = ownerData(identity);
  return std::any_of(readers.begin(), readers.end(), [&](const std::string* d) { return *d == owner; });
}

void WriterBase::waitForAcknowledgements(std::chrono::milliseconds timeout) const {
  const dds_return_t rc = dds_wait_for_acks(handle(), DDS_MSECS(timeout.count()));
  if (rc != DDS_RETCODE_TIMEOUT) check(rc, "dds_wait_for_acks");
}

ReaderBase::ReaderBase(const Participant& participant, dds_entity_t topic, const Qos& qos)
    : Entity([&] {
        const auto own = withIdentity(participant, qos);
        return check(dds_create_reader(participant.handle(), topic, own ? own->get() : qos.get(), nullptr),
                     "dds_create_reader");
      }()) {
  check(dds_set_status_mask(handle(), DDS_SUBSCRIPTION_MATCHED_STATUS), "dds_set_status_mask(reader)");
}

std::int32_t ReaderBase::matchedWriters() const {
  dds_subscription_matched_status_t status;
  check(dds_get_subscription_matched_status(handle(), &status), "dds_get_subscription_matched_status");
  return static_cast<std::int32_t>(status.current_count);
}

bool ReaderBase::matchesWriterOf(const std::string& identity) const {
  const std::string owner = ownerData(identity);
  for (const auto writer : matchedHandles(handle(), dds_get_matched_publications, "dds_get_matched_publications")) {
    const auto data = endpointData(dds_get_matched_publication_data(handle(), writer));
    if (data && userData(data->qos) == owner) return true;
  }
  return false;
}

ReadCondition::ReadCondition(const ReaderBase& reader)
    : Entity(check(dds_create_readcondition(reader.handle(), DDS_ANY_STATE), "dds_create_readcondition")) {}

GuardCondition::GuardCondition(const Participant& participant)
    : Entity(check(dds_create_guardcondition(participant.handle()), "dds_create_guardcondition")) {}

void GuardCondition::trigger() { check(dds_set_guardcondition(handle(), true), "dds_set_guardcondition"); }

bool GuardCondition::triggered() const {
  bool value = false;
  check(dds_read_guardcondition(handle(), &value), "dds_read_guardcondition");
  return value;
}

WaitSet::WaitSet(const Participant& participant)
    : Entity(check(dds_create_waitset(participant.handle()), "dds_create_waitset")) {}

void WaitSet::attach(dds_entity_t entity, dds_attach_t token) {
  check(dds_waitset_attach(handle(), entity, token), "dds_waitset_attach");
}

std::vector<dds_attach_t> WaitSet::wait(std::chrono::milliseconds timeout) {
  dds_attach_t triggered[64];
  const dds_return_t n = check(dds_waitset_wait(handle(), triggered, 64, DDS_MSECS(timeout.count())), "dds_waitset_wait");
  return {triggered, triggered + std::min<dds_return_t>(n, 64)};
}

}  // namespace wsn::dds
