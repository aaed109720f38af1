// The end-to-end benchmark's load and stopwatch (make bench, scripts/bench_node.py): publishes
// mavros_msgs/RCOut (as a ShapeShifter with its exact definition and md5sum) at --rate-hz with
// hover-like PWM plus noise, stamped now, sensor_msgs/BatteryState at --battery-rate-hz and, with
// --esc-rate-hz, mavros_msgs/ESCTelemetry (every ESC in each message), for --duration-s; times
// every propulsion_estimator/PropulsionTotals on --estimate-topic from the RCOut stamp it carries
// to its receipt; reads the system under test's CPU time (utime + stime of
// /proc/<pid>/stat) and resident memory (VmRSS) before and after the load. Writes one JSON object
// and the latencies themselves (--latencies-file): scripts/bench_node.py pools them over its rounds
// and takes the percentiles.
// An estimate is timed when roscpp's network thread has read it (InlineCallbackQueue, as
// estimator_node receives): the hand-over to a spinner thread is the probe's own cost, not the
// system's under test.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <mutex>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <CLI/CLI.hpp>
#include <ros/ros.h>
#include <sensor_msgs/BatteryState.h>
#include <unistd.h>

#include "propulsion_estimator/PropulsionTotals.h"
#include "propulsion_estimator/common/mavros_topics.h"
#include "propulsion_estimator/codecs/esc_telemetry_codec.h"
#include "propulsion_estimator/ros/inline_callback_queue.h"
#include "propulsion_estimator/codecs/rcout_codec.h"

namespace pe = propulsion_estimator;

namespace {

struct Options {
  double duration_s = 60.0;
  double rate_hz = 400.0;
  double battery_rate_hz = 1.0;
  int channels = 8;
  double pwm_us = 1500.0;
  double pwm_noise_us = 4.0;
  double voltage_v = 11.5;
  std::string rc_out_topic = "/mavros/rc/out";
  std::string battery_topic = "/mavros/battery";
  double esc_rate_hz = 0.0;  // mavros_msgs/ESCTelemetry, every ESC in each message; 0: none
  std::string esc_topic = pe::kEscTelemetryTopic;
  std::string estimate_topic;  // "": the system under test answers nothing (the transport floor)
  int pid = 0;
  double connect_timeout_s = 120.0;
  double drain_s = 2.0;
  std::string json;
  std::string latencies_file;
};

// CPU seconds (user + system) the process has used so far, from /proc/<pid>/stat.
double cpuSeconds(int pid) {
  std::ifstream file("/proc/" + std::to_string(pid) + "/stat");
  std::string stat((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  // The command name (field 2) may hold spaces; the fields after its closing parenthesis are
  // state (3) ... utime (14), stime (15).
  const std::size_t close = stat.rfind(')');
  if (close == std::string::npos) throw std::runtime_error("/proc/" + std::to_string(pid) + "/stat: not readable");
  std::istringstream fields(stat.substr(close + 1));
  std::string field;
  double utime = 0.0, stime = 0.0;
  for (int index = 3; index <= 15 && fields >> field; ++index) {
    if (index == 14) utime = std::stod(field);
    if (index == 15) stime = std::stod(field);
  }
  return (utime + stime) / static_cast<double>(sysconf(_SC_CLK_TCK));
}

// Resident memory in kB, from the VmRSS line of /proc/<pid>/status.
long residentKb(int pid) {
  std::ifstream file("/proc/" + std::to_string(pid) + "/status");
  std::string key;
  long value = 0;
  std::string line;
  while (std::getline(file, line)) {
    std::istringstream fields(line);
    if (fields >> key >> value && key == "VmRSS:") return value;
  }
  throw std::runtime_error("/proc/" + std::to_string(pid) + "/status: no VmRSS");
}

std::string number(double value) {
  if (!std::isfinite(value)) return "null";
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", value);
  return text;
}

class Probe {
 public:
  explicit Probe(const Options& options) : options_(options) {
    ros::AdvertiseOptions rc_out(options.rc_out_topic, 100, pe::kRcOutMd5Sum, pe::kRcOutDataType,
                                 pe::rcOutDefinition());
    rc_out_pub_ = nh_.advertise(rc_out);
    battery_pub_ = nh_.advertise<sensor_msgs::BatteryState>(options.battery_topic, 5);
    if (options.esc_rate_hz > 0.0) {
      ros::AdvertiseOptions esc(options.esc_topic, 100, pe::kEscTelemetryMd5Sum, pe::kEscTelemetryDataType,
                                pe::escTelemetryDefinition());
      esc_pub_ = nh_.advertise(esc);
    }
    if (!options.estimate_topic.empty()) {
      latencies_s_.reserve(static_cast<std::size_t>(options.duration_s * options.rate_hz) + 1);
      ros::NodeHandle estimate_nh(nh_);
      estimate_nh.setCallbackQueue(&estimate_queue_);
      estimate_sub_ = estimate_nh.subscribe(options.estimate_topic, 1000, &Probe::onEstimate, this,
                                    ros::TransportHints().tcpNoDelay());
    }
  }

  int run() {
    ros::AsyncSpinner spinner(1);
    spinner.start();
    if (!waitForConnections()) return 1;
    sendBattery();  // the estimator refuses RCOut until it has a voltage
    std::this_thread::sleep_for(std::chrono::milliseconds(200));

    std::cout << "bench_probe: load started" << std::endl;  // scripts/bench_node.py times its callgrind run from here
    const double cpu_start = options_.pid ? cpuSeconds(options_.pid) : NAN;
    const long rss_start_kb = options_.pid ? residentKb(options_.pid) : 0;
    const auto start = std::chrono::steady_clock::now();
    const auto period = std::chrono::duration<double>(1.0 / options_.rate_hz);
    const auto battery_period = std::chrono::duration<double>(1.0 / options_.battery_rate_hz);
    const long messages = std::lround(options_.duration_s * options_.rate_hz);
    auto next_battery = start + std::chrono::duration_cast<std::chrono::steady_clock::duration>(battery_period);
    const auto esc_period = std::chrono::duration<double>(options_.esc_rate_hz > 0.0 ? 1.0 / options_.esc_rate_hz : 1e9);
    auto next_esc = start + std::chrono::duration_cast<std::chrono::steady_clock::duration>(esc_period);
    std::mt19937 random(1);
    std::normal_distribution<double> noise(0.0, options_.pwm_noise_us);
    pe::RcOutMessage message;
    message.channels.resize(static_cast<std::size_t>(options_.channels));
    for (long k = 0; k < messages && ros::ok(); ++k) {
      std::this_thread::sleep_until(start + std::chrono::duration_cast<std::chrono::steady_clock::duration>(period * k));
      if (std::chrono::steady_clock::now() >= next_battery) {
        sendBattery();
        next_battery += std::chrono::duration_cast<std::chrono::steady_clock::duration>(battery_period);
      }
      if (options_.esc_rate_hz > 0.0 && std::chrono::steady_clock::now() >= next_esc) {
        sendEsc();
        next_esc += std::chrono::duration_cast<std::chrono::steady_clock::duration>(esc_period);
      }
      for (std::uint16_t& channel : message.channels) {
        channel = static_cast<std::uint16_t>(std::lround(options_.pwm_us + noise(random)));
      }
      message.header.seq = static_cast<std::uint32_t>(k);
      message.header.stamp = ros::Time::now();
      rc_out_pub_.publish(pe::encodeRcOut(message));
      ++sent_;
    }
    const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const double cpu_end = options_.pid ? cpuSeconds(options_.pid) : NAN;
    const long rss_end_kb = options_.pid ? residentKb(options_.pid) : 0;
    // The answers to the last messages are still on their way.
    const auto drain_end = std::chrono::steady_clock::now() + std::chrono::duration<double>(options_.drain_s);
    while (!options_.estimate_topic.empty() && received() < sent_ && std::chrono::steady_clock::now() < drain_end) {
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    spinner.stop();
    return write(wall_s, cpu_end - cpu_start, rss_start_kb, rss_end_kb);
  }

 private:
  bool waitForConnections() {
    const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(options_.connect_timeout_s);
    while (ros::ok() && ros::WallTime::now() < deadline) {
      const bool answers = options_.estimate_topic.empty() || estimate_sub_.getNumPublishers() > 0;
      const bool esc = options_.esc_rate_hz <= 0.0 || esc_pub_.getNumSubscribers() > 0;
      if (rc_out_pub_.getNumSubscribers() > 0 && battery_pub_.getNumSubscribers() > 0 && answers && esc) return true;
      ros::WallDuration(0.05).sleep();
    }
    std::cerr << "bench_probe: nothing subscribed to " << options_.rc_out_topic << " and " << options_.battery_topic
              << (options_.estimate_topic.empty() ? "" : " or published " + options_.estimate_topic) << " within "
              << options_.connect_timeout_s << " s\n";
    return false;
  }

  void sendBattery() {
    sensor_msgs::BatteryState battery;
    battery.header.stamp = ros::Time::now();
    battery.voltage = static_cast<float>(options_.voltage_v);
    battery.current = -20.0f;
    battery.percentage = 0.8f;
    battery.present = true;
    battery_pub_.publish(battery);
    ++battery_sent_;
  }

  // Every ESC at a hover's speed and current, with noise, as ArduPilot's ESC_TELEMETRY reports them;
  // from a random stream of its own, so that the RCOut load is the same with telemetry as without.
  void sendEsc() {
    std::normal_distribution<double> noise(0.0, 1.0);
    std::mt19937& random = esc_random_;
    pe::EscTelemetry telemetry;
    telemetry.stamp_s = ros::Time::now().toSec();
    telemetry.escs.resize(static_cast<std::size_t>(options_.channels));
    for (pe::EscReport& esc : telemetry.escs) {
      esc.stamp_s = telemetry.stamp_s;
      esc.rpm = 6000.0 + 50.0 * noise(random);
      esc.current_a = 4.0 + 0.1 * noise(random);
      esc.voltage_v = options_.voltage_v;
      esc.temperature_c = 35.0;
      esc.count = static_cast<int>(esc_sent_ % 65536);
    }
    esc_pub_.publish(pe::encodeEscTelemetry(telemetry, false));
    ++esc_sent_;
  }

  void onEstimate(const pe::PropulsionTotals::ConstPtr& totals) {
    const double latency_s = (ros::Time::now() - totals->header.stamp).toSec();
    std::lock_guard<std::mutex> lock(mutex_);
    latencies_s_.push_back(latency_s);
  }

  long received() {
    std::lock_guard<std::mutex> lock(mutex_);
    return static_cast<long>(latencies_s_.size());
  }

  int write(double wall_s, double cpu_s, long rss_start_kb, long rss_end_kb) {
    std::vector<double> sorted;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      sorted = latencies_s_;
    }
    std::sort(sorted.begin(), sorted.end());
    const bool timed = !options_.estimate_topic.empty();
    std::ostringstream json;
    json << "{\"rc_out_sent\": " << sent_ << ", \"battery_sent\": " << battery_sent_ << ", \"esc_sent\": " << esc_sent_
         << ", \"rate_hz\": " << number(options_.rate_hz) << ", \"channels\": " << options_.channels
         << ", \"wall_s\": " << number(wall_s) << ", \"estimates_received\": "
         << (timed ? std::to_string(sorted.size()) : "null")
         << ", \"cpu_s\": " << number(cpu_s) << ", \"cpu_percent\": " << number(100.0 * cpu_s / wall_s)
         << ", \"rss_start_kb\": " << rss_start_kb << ", \"rss_end_kb\": " << rss_end_kb << "}\n";
    if (!options_.latencies_file.empty()) {
      std::ofstream latencies(options_.latencies_file);
      for (double latency_s : sorted) latencies << number(1e3 * latency_s) << "\n";
      if (!latencies) {
        std::cerr << "bench_probe: cannot write " << options_.latencies_file << "\n";
        return 1;
      }
    }
    if (options_.json.empty()) {
      std::cout << json.str();
      return 0;
    }
    std::ofstream file(options_.json);
    file << json.str();
    if (!file) {
      std::cerr << "bench_probe: cannot write " << options_.json << "\n";
      return 1;
    }
    return 0;
  }

  Options options_;
  ros::NodeHandle nh_;
  long sent_ = 0, battery_sent_ = 0, esc_sent_ = 0;
  std::mt19937 esc_random_{2};
  std::mutex mutex_;
  std::vector<double> latencies_s_;
  pe::InlineCallbackQueue estimate_queue_;
  ros::Publisher rc_out_pub_, battery_pub_, esc_pub_;
  // Last, so destroyed first: its callback uses the members above.
  ros::Subscriber estimate_sub_;
};

}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "bench_probe", ros::init_options::AnonymousName);
  Options options;
  CLI::App app{"Publishes RCOut and BatteryState at a fixed rate and times the estimates (make bench)."};
  app.add_option("--duration-s", options.duration_s, "seconds of load")->check(CLI::PositiveNumber);
  app.add_option("--rate-hz", options.rate_hz, "RCOut rate")->check(CLI::PositiveNumber);
  app.add_option("--battery-rate-hz", options.battery_rate_hz, "BatteryState rate")->check(CLI::PositiveNumber);
  app.add_option("--channels", options.channels, "RCOut channels")->check(CLI::Range(1, 32));
  app.add_option("--pwm-us", options.pwm_us, "mean PWM of every channel");
  app.add_option("--pwm-noise-us", options.pwm_noise_us, "standard deviation of the PWM noise");
  app.add_option("--voltage-v", options.voltage_v, "battery voltage");
  app.add_option("--rc-out-topic", options.rc_out_topic);
  app.add_option("--battery-topic", options.battery_topic);
  app.add_option("--esc-rate-hz", options.esc_rate_hz, "mavros_msgs/ESCTelemetry rate, every ESC in each; 0: none")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--esc-topic", options.esc_topic);
  app.add_option("--estimate-topic", options.estimate_topic, "PropulsionTotals to time; none: no latency");
  app.add_option("--pid", options.pid, "process under test (CPU time and VmRSS)");
  app.add_option("--connect-timeout-s", options.connect_timeout_s);
  app.add_option("--drain-s", options.drain_s, "longest wait for the last estimates after the load");
  app.add_option("--json", options.json, "output file; none: stdout");
  app.add_option("--latencies-file", options.latencies_file, "every latency measured, in ms, one per line, sorted");
  CLI11_PARSE(app, argc, argv);
  try {
    Probe probe(options);
    return probe.run();
  } catch (const std::exception& e) {
    std::cerr << "bench_probe: " << e.what() << "\n";
    return 1;
  }
}
