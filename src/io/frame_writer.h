// Frames written off the render threads: a writer thread takes frames from a short queue and
// encodes and writes them (writeFrame: in order, so the files and the reuse of a still frame's
// encoding are what writing them one by one gives), while the renderer goes on with the next
// block. The queue holds at most `capacity` frames, so memory stays bounded (the memory plan counts
// them); a full queue makes the renderer wait.
#pragma once

#include <condition_variable>
#include <deque>
#include <exception>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "streyes/frame_image.h"
#include "streyes/image_io.h"

namespace streyes {

class FrameWriter {
  public:
    explicit FrameWriter(int capacity = 2);
    ~FrameWriter();  // waits for what is queued; errors then are dropped (call finish() to see them)

    // Queues `image` to be written to each output (path, channel mode, quantization). Throws the error of an earlier
    // write, if one failed: the render stops there, as if it had written the frame itself.
    void write(const FrameImage& image, std::vector<FrameOutput> outputs);
    // The same without a copy: `image`'s pixels are queued and `image` gets in exchange those of a
    // frame already written (once the queue has cycled, of the same shape: the renderer assembles
    // its next frame in them with no new page), or nothing.
    void handOver(FrameImage& image, std::vector<FrameOutput> outputs);
    // Waits until every queued frame is written; throws the first write error.
    void finish();

  private:
    struct Job {
        std::unique_ptr<FrameImage> image;
        std::vector<FrameOutput> outputs;
    };
    void run();
    void rethrow();
    std::unique_ptr<FrameImage> takeSpare();
    void queue(std::unique_ptr<FrameImage> image, std::vector<FrameOutput> outputs);

    const size_t capacity_;
    std::mutex mutex_;
    std::condition_variable changed_;
    std::deque<Job> queue_;
    // Frames already written, kept for the next frames: copying into a buffer of the right size
    // touches no new page (a fresh 4.6 MB copy a frame was mapped, faulted in and unmapped each
    // time: half the CPU of a 64-frame still shot), and handOver swaps them out with no copy at
    // all. At most capacity + 1 exist at once.
    std::vector<std::unique_ptr<FrameImage>> spare_;
    bool busy_ = false, stopping_ = false;
    std::exception_ptr error_;
    std::thread thread_;
};

}  // namespace streyes
