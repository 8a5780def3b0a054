#include <lcm/lcm-cpp.hpp>

#include <cstdlib>
#include <stdexcept>

#include "relplane/common/bus.hpp"

namespace relplane::bus {
namespace {

class LcmBus final : public Bus {
 public:
  explicit LcmBus(const std::string& url) : lcm_(url), url_(url) {
    if (!lcm_.good()) {
      throw std::runtime_error("cannot open the LCM bus '" + (url.empty() ? "(default)" : url) +
                               "' (udpm needs a multicast route: ip route add 224.0.0.0/4 dev lo)");
    }
  }

  bool PublishRaw(const std::string& channel, const uint8_t* data, size_t size) override {
    return lcm_.publish(channel, data, static_cast<unsigned int>(size)) == 0;
  }

  void SubscribeRaw(const std::string& channel, RawHandler handler, int queue_capacity) override {
    handlers_.push_back(std::make_unique<Entry>(Entry{std::move(handler)}));
    // LCM treats channel names as regular expressions; relplane channels are plain words.
    lcm::Subscription* sub =
        lcm_.subscribeFunction("^" + channel + "$", &LcmBus::Dispatch, handlers_.back().get());
    if (sub != nullptr) sub->setQueueCapacity(queue_capacity);
  }

  int Handle(int timeout_ms) override { return lcm_.handleTimeout(timeout_ms); }

  const std::string& Url() const override { return url_; }

 private:
  struct Entry {
    RawHandler handler;
  };

  static void Dispatch(const lcm::ReceiveBuffer* rbuf, const std::string& channel, Entry* entry) {
    entry->handler(channel, static_cast<const uint8_t*>(rbuf->data), rbuf->data_size);
  }

  lcm::LCM lcm_;
  std::string url_;
  std::vector<std::unique_ptr<Entry>> handlers_;
};

}  // namespace

std::string ResolveUrl(const std::string& flag) {
  if (!flag.empty()) return flag;
  const char* env = std::getenv("LCM_DEFAULT_URL");
  return env != nullptr ? std::string(env) : std::string();
}

std::string ResolveCloudUrl(const std::string& flag, const std::string& main_url) {
  return flag.empty() ? main_url : flag;
}

std::unique_ptr<Bus> OpenLcmBus(const std::string& url) { return std::make_unique<LcmBus>(url); }

}  // namespace relplane::bus
