#include "io/frame_writer.h"

#include "streyes/image_io.h"

namespace streyes {

FrameWriter::FrameWriter(int capacity) : capacity_(size_t(capacity < 1 ? 1 : capacity)), thread_([this] { run(); }) {}

FrameWriter::~FrameWriter() {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        stopping_ = true;
    }
    changed_.notify_all();
    thread_.join();
}

void FrameWriter::rethrow() {
    if (error_) std::rethrow_exception(error_);
}

std::unique_ptr<FrameImage> FrameWriter::takeSpare() {
    std::lock_guard<std::mutex> lock(mutex_);
    if (spare_.empty()) return std::make_unique<FrameImage>();
    std::unique_ptr<FrameImage> spare = std::move(spare_.back());
    spare_.pop_back();
    return spare;
}

void FrameWriter::queue(std::unique_ptr<FrameImage> image, std::vector<FrameOutput> outputs) {
    std::unique_lock<std::mutex> lock(mutex_);
    changed_.wait(lock, [this] { return error_ || queue_.size() < capacity_; });
    rethrow();
    queue_.push_back({std::move(image), std::move(outputs)});
    changed_.notify_all();
}

void FrameWriter::write(const FrameImage& image, std::vector<FrameOutput> outputs) {
    std::unique_ptr<FrameImage> copy = takeSpare();  // the caller keeps its image
    *copy = image;
    queue(std::move(copy), std::move(outputs));
}

void FrameWriter::handOver(FrameImage& image, std::vector<FrameOutput> outputs) {
    std::unique_ptr<FrameImage> taken = takeSpare();
    std::swap(*taken, image);
    queue(std::move(taken), std::move(outputs));
}

void FrameWriter::finish() {
    std::unique_lock<std::mutex> lock(mutex_);
    changed_.wait(lock, [this] { return error_ || (queue_.empty() && !busy_); });
    rethrow();
}

void FrameWriter::run() {
    std::unique_lock<std::mutex> lock(mutex_);
    for (;;) {
        changed_.wait(lock, [this] { return stopping_ || !queue_.empty(); });
        if (queue_.empty()) return;  // stopping, nothing left
        Job job = std::move(queue_.front());
        queue_.pop_front();
        busy_ = true;
        lock.unlock();
        std::exception_ptr failed;
        try {
            if (!error_)
                for (const FrameOutput& o : job.outputs) writeFrame(o.path, *job.image, o.mode, o.quantize, o.window);
        } catch (...) {
            failed = std::current_exception();
        }
        lock.lock();
        if (spare_.size() <= capacity_) spare_.push_back(std::move(job.image));
        busy_ = false;
        if (failed && !error_) error_ = failed;
        if (error_) queue_.clear();  // the render stops: nothing after a failed frame is written
        changed_.notify_all();
    }
}

}  // namespace streyes
