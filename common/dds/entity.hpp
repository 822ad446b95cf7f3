// A small RAII layer over the Cyclone DDS C API: one move-only owner per handle, every return
// code checked through check(), topics bound to their sample type so that a writer or reader of
// another type does not compile, and loaned take with the loan always returned.
#pragma once

#include <dds/dds.h>

#include <chrono>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <unordered_map>
#include <utility>
#include <vector>

namespace wsn::dds {

/// A failed Cyclone call: what() names the operation and dds_strretcode's reason.
class DdsError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Throws DdsError when rc is a Cyclone error code; returns rc otherwise.
dds_return_t check(dds_return_t rc, const std::string& what);

/// Owner of one Cyclone entity handle; deleting it deletes its children too.
class Entity {
 public:
  Entity() = default;
  explicit Entity(dds_entity_t handle) : handle_(handle) {}
  Entity(const Entity&) = delete;
  Entity& operator=(const Entity&) = delete;
  Entity(Entity&& other) noexcept : handle_(std::exchange(other.handle_, 0)) {}
  Entity& operator=(Entity&& other) noexcept {
    if (this != &other) {
      reset();
      handle_ = std::exchange(other.handle_, 0);
    }
    return *this;
  }
  ~Entity() { reset(); }

  dds_entity_t handle() const { return handle_; }
  explicit operator bool() const { return handle_ > 0; }

 protected:
  void reset() noexcept {
    if (handle_ > 0) dds_delete(handle_);  // never throws: a destructor must not
    handle_ = 0;
  }
  /// Lets go of the handle without deleting it (for a view of an entity another owner holds).
  void release() noexcept { handle_ = 0; }

 private:
  dds_entity_t handle_ = 0;
};

/// Who an endpoint belongs to. The start barrier counts matched cluster roles; a viewer
/// (wsntrack watch, examples/, any program built from the IDL) must never stand in for a role
/// that has not matched yet, so role endpoints carry a marker in their user data and viewers not.
enum class Endpoint { kRole, kViewer };

/// A QoS object, deleted on scope exit.
class Qos {
 public:
  Qos() : qos_(dds_create_qos()) {}
  Qos(const Qos&) = delete;
  Qos& operator=(const Qos&) = delete;
  Qos(Qos&& other) noexcept : qos_(std::exchange(other.qos_, nullptr)) {}
  Qos& operator=(Qos&&) = delete;
  ~Qos() {
    if (qos_ != nullptr) dds_delete_qos(qos_);
  }
  dds_qos_t* get() const { return qos_; }

  /// Reliable, KEEP_ALL, volatile: the lockstep batches, where no tick may be lost.
  static Qos reliableKeepAll(Endpoint owner = Endpoint::kRole);
  /// Reliable, KEEP_LAST 1 per instance, TRANSIENT_LOCAL: process status for late joiners.
  static Qos lastValueTransientLocal(Endpoint owner = Endpoint::kRole);
  /// Best effort, KEEP_ALL, volatile: a viewer's reader that must never hold a writer back.
  static Qos bestEffort(Endpoint owner = Endpoint::kViewer);

  /// Puts the endpoint in DDS partition `name`: it matches only endpoints of the same topic in
  /// that partition, so samples meant for one process are sent to that process alone.
  Qos&& inPartition(const std::string& name) &&;
  /// The same with several partitions: the endpoint matches those of any of them.
  Qos&& inPartitions(const std::vector<std::string>& names) &&;
  /// KEEP_ALL history instead: a reader that must see every sample of an instance, not only its last.
  Qos&& keepingAll() &&;

 private:
  dds_qos_t* qos_;
};

/// A Cyclone domain created from an explicit XML configuration (never the default one,
/// which would multicast on the outer interface).
class Domain : public Entity {
 public:
  Domain(dds_domainid_t id, const std::string& config_xml);
  dds_domainid_t id() const { return id_; }

 private:
  dds_domainid_t id_;
};

/// A participant; `identity` names the role process it belongs to ("supernode 2 from 60"): every
/// role endpoint it makes carries it after the role marker in its user data, so that a peer can
/// tell a restarted process's endpoints from the dead one's, which stay matched until their lease
/// ends. Empty for a viewer or the launcher's observer.
class Participant : public Entity {
 public:
  explicit Participant(dds_domainid_t domain, std::string identity = "");
  /// A view of `shared` under another identity: the role threads of one process (a group of
  /// supernodes) share one participant, so that the run has fewer participants to discover. The
  /// view deletes nothing; each role deletes its own endpoints, and `shared` must outlive it.
  Participant(const Participant& shared, std::string identity);
  Participant(const Participant&) = delete;
  Participant& operator=(const Participant&) = delete;
  ~Participant() {
    if (!owned_) release();
  }
  const std::string& identity() const { return identity_; }

 private:
  std::string identity_;
  bool owned_ = true;
};

/// Binds a generated C sample type to its idlc descriptor. Specialised once per type, with a
/// `static constexpr const dds_topic_descriptor_t& descriptor` (see role_runtime.hpp), so that
/// the pairing of type and descriptor is written in one place and a type without one does not
/// compile as a topic.
template <typename Sample>
struct TopicType;

/// Creates the Cyclone topic; a descriptor whose size is not the sample's (a wrong TopicType
/// binding) is rejected here rather than corrupting memory on the first take.
dds_entity_t createTopic(const Participant& participant, const dds_topic_descriptor_t& descriptor,
                         std::size_t sample_size, const std::string& name);

/// A topic of one IDL type: writers and readers are made only from a topic of their own type.
template <typename Sample>
class Topic : public Entity {
 public:
  Topic(const Participant& participant, const std::string& name)
      : Entity(createTopic(participant, TopicType<Sample>::descriptor, sizeof(Sample), name)) {}
};

/// What every writer has whatever its type: matching and acknowledgements (the start barrier
/// sees writers of several types through it).
class WriterBase : public Entity {
 public:
  /// Number of readers currently matched.
  std::int32_t matchedReaders() const;
  /// Number of matched readers that belong to cluster roles (Endpoint::kRole), viewers excluded.
  std::int32_t matchedRoleReaders() const;
  /// Whether a reader of the role process named `identity` (Participant::identity) is matched.
  bool matchesReaderOf(const std::string& identity) const;
  /// Blocks until every matched reader acknowledged everything written (used once at exit).
  void waitForAcknowledgements(std::chrono::milliseconds timeout) const;

 protected:
  WriterBase(const Participant& participant, dds_entity_t topic, const Qos& qos);

 private:
  /// The user data of each matched reader (nothing for one that unmatched meanwhile).
  std::vector<const std::string*> matchedReaderData() const;
  /// Each matched reader's user data, looked up once: it never changes, and looking it up again
  /// on every discovery event made a 70-process start-up quadratic in DDS.
  mutable std::unordered_map<dds_instance_handle_t, std::string> reader_data_;
};

/// A writer of one sample type (a generated C struct).
template <typename Sample>
class Writer : public WriterBase {
 public:
  Writer(const Participant& participant, const Topic<Sample>& topic, const Qos& qos)
      : WriterBase(participant, topic.handle(), qos) {}
  /// Serialises the sample and sends it.
  void write(const Sample& sample) { check(dds_write(handle(), &sample), "dds_write"); }
};

/// What every reader has whatever its type: matching (the start barrier and the role loop see
/// readers of several types through it).
class ReaderBase : public Entity {
 public:
  /// Number of writers currently matched.
  std::int32_t matchedWriters() const;
  /// Whether a writer of the role process named `identity` (Participant::identity) is matched.
  bool matchesWriterOf(const std::string& identity) const;

 protected:
  ReaderBase(const Participant& participant, dds_entity_t topic, const Qos& qos);
};

/// A reader of one sample type (a generated C struct).
template <typename Sample>
class Reader : public ReaderBase {
 public:
  Reader(const Participant& participant, const Topic<Sample>& topic, const Qos& qos)
      : ReaderBase(participant, topic.handle(), qos) {}
  /// Takes everything available and calls f(const Sample&) for each valid sample, with the
  /// loan returned before this returns (even when f throws). Returns the number of samples.
  template <typename F>
  std::size_t take(F&& f) {
    static_assert(std::is_invocable_v<F&, const Sample&>, "take() calls f with the reader's own sample type");
    constexpr std::size_t kBatch = 64;
    std::size_t total = 0;
    while (true) {
      void* samples[kBatch] = {nullptr};
      dds_sample_info_t infos[kBatch];
      const dds_return_t n = dds_take(handle(), samples, infos, kBatch, kBatch);
      check(n, "dds_take");
      if (n == 0) return total;
      struct LoanGuard {
        dds_entity_t reader;
        void** buffer;
        dds_return_t count;
        ~LoanGuard() { dds_return_loan(reader, buffer, count); }
      } guard{handle(), samples, n};
      for (dds_return_t i = 0; i < n; ++i) {
        if (!infos[i].valid_data) continue;
        f(*static_cast<const Sample*>(samples[i]));
        ++total;
      }
    }
  }
};

/// A read condition that triggers while the reader holds any sample.
class ReadCondition : public Entity {
 public:
  explicit ReadCondition(const ReaderBase& reader);
};

/// A condition set from another thread (or a signal handler) to wake a waitset.
class GuardCondition : public Entity {
 public:
  explicit GuardCondition(const Participant& participant);
  void trigger();
  bool triggered() const;
};

/// A waitset; entities are attached with an argument that wait() reports back.
class WaitSet : public Entity {
 public:
  explicit WaitSet(const Participant& participant);
  void attach(dds_entity_t entity, dds_attach_t token);
  /// Waits up to `timeout`; returns the tokens of the triggered entities (empty on timeout).
  std::vector<dds_attach_t> wait(std::chrono::milliseconds timeout);
};

}  // namespace wsn::dds
