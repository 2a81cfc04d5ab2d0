// OpenEXR through its C++ API (Imf::OutputFile, Imf::InputFile) over in-memory streams. See
// exr_io.h for the contract.
#include "image/exr_io.h"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <string>

#include <Iex.h>
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfStringAttribute.h>

#include "core/error.h"
#include "image/image_io.h"
#include "scene/text_input.h"

namespace fs = std::filesystem;

namespace vkray {
namespace {

// OpenEXR's messages may span lines; ours are one line.
std::string oneLine(std::string s) {
    std::replace(s.begin(), s.end(), '\n', ' ');
    return s;
}

class MemoryOStream : public Imf::OStream {
public:
    MemoryOStream() : Imf::OStream("memory") {}
    void write(const char c[], int n) override {
        if (pos_ + size_t(n) > bytes_.size()) bytes_.resize(pos_ + size_t(n));
        std::memcpy(bytes_.data() + pos_, c, size_t(n));
        pos_ += size_t(n);
    }
    uint64_t tellp() override { return pos_; }
    void seekp(uint64_t pos) override { pos_ = size_t(pos); }
    std::vector<unsigned char>& bytes() { return bytes_; }

private:
    std::vector<unsigned char> bytes_;
    size_t pos_ = 0;
};

class MemoryIStream : public Imf::IStream {
public:
    explicit MemoryIStream(const std::vector<unsigned char>& bytes) : Imf::IStream("memory"), bytes_(bytes) {}
    bool read(char c[], int n) override {
        if (n < 0 || pos_ > bytes_.size() || size_t(n) > bytes_.size() - pos_)
            throw Iex::InputExc("the file ends early (truncated)");
        std::memcpy(c, bytes_.data() + pos_, size_t(n));
        pos_ += size_t(n);
        return pos_ < bytes_.size();
    }
    uint64_t tellg() override { return pos_; }
    void seekg(uint64_t pos) override { pos_ = size_t(std::min<uint64_t>(pos, bytes_.size() + 1)); }
    void clear() override {}

private:
    const std::vector<unsigned char>& bytes_;
    size_t pos_ = 0;
};

const char* const kRgb[] = {"R", "G", "B"};
const char* const kY[] = {"Y"};

// The channel names of an image of `channels` channels, in their interleaved order.
std::vector<const char*> channelNames(int channels) {
    return channels == 3 ? std::vector<const char*>(kRgb, kRgb + 3) : std::vector<const char*>(kY, kY + 1);
}

Imf::Header headerFor(const fs::path& path, const Image& image, const ImageMeta& meta) {
    const int dw = meta.displayWidth > 0 ? meta.displayWidth : image.width;
    const int dh = meta.displayHeight > 0 ? meta.displayHeight : image.height;
    if (meta.displayWidth < 0 || meta.displayHeight < 0 || meta.x0 < 0 || meta.y0 < 0 ||
        int64_t(meta.x0) + image.width > dw || int64_t(meta.y0) + image.height > dh)
        throw fileError(path, "cannot write: the " + std::to_string(image.width) + "x" + std::to_string(image.height) +
                                  " image at (" + std::to_string(meta.x0) + ", " + std::to_string(meta.y0) +
                                  ") lies outside its " + std::to_string(dw) + "x" + std::to_string(dh) +
                                  " display window");
    const Imath::Box2i display(Imath::V2i(0, 0), Imath::V2i(dw - 1, dh - 1));
    const Imath::Box2i data(Imath::V2i(meta.x0, meta.y0),
                            Imath::V2i(meta.x0 + image.width - 1, meta.y0 + image.height - 1));
    Imf::Header header(display, data, 1.0f, Imath::V2f(0, 0), 1.0f, Imf::INCREASING_Y, Imf::ZIP_COMPRESSION);
    for (const char* name : channelNames(image.channels)) header.channels().insert(name, Imf::Channel(Imf::FLOAT));
    for (const auto& [name, value] : meta.attributes) {
        if (name.empty() || header.find(name) != header.end())
            throw fileError(path, "cannot write the attribute '" + name + "': the name is empty or a standard EXR one");
        header.insert(name, Imf::StringAttribute(value));
    }
    return header;
}

}  // namespace

bool hasExrMagic(const std::vector<unsigned char>& bytes) {
    static const unsigned char kMagic[4] = {0x76, 0x2f, 0x31, 0x01};
    return bytes.size() >= 4 && std::memcmp(bytes.data(), kMagic, 4) == 0;
}

std::vector<unsigned char> encodeExr(const fs::path& path, const Image& image, const ImageMeta& meta) {
    const Imf::Header header = headerFor(path, image, meta);
    const Imath::Box2i& data = header.dataWindow();
    const size_t xStride = sizeof(float) * size_t(image.channels);
    MemoryOStream stream;
    try {
        Imf::FrameBuffer frame;
        const std::vector<const char*> names = channelNames(image.channels);
        for (size_t c = 0; c < names.size(); ++c)
            frame.insert(names[c], Imf::Slice::Make(Imf::FLOAT, image.data.data() + c, data, xStride,
                                                    xStride * size_t(image.width)));
        Imf::OutputFile file(stream, header, 1);
        file.setFrameBuffer(frame);
        file.writePixels(image.height);
    } catch (const std::exception& e) {
        throw fileError(path, "cannot encode the EXR: " + oneLine(e.what()));
    }
    return std::move(stream.bytes());
}

Image decodeExr(const fs::path& path, const std::vector<unsigned char>& bytes, ImageMeta* meta) {
    MemoryIStream stream(bytes);
    try {
        Imf::InputFile file(stream, 1);
        const Imf::Header& header = file.header();
        const Imath::Box2i data = header.dataWindow(), display = header.displayWindow();
        const int64_t w = int64_t(data.max.x) - data.min.x + 1, h = int64_t(data.max.y) - data.min.y + 1;
        if (w <= 0 || h <= 0 || w > kMaxImageDimension || h > kMaxImageDimension || uint64_t(w * h) > kMaxReadPixels)
            throw fileError(path, "implausible EXR data window " + std::to_string(w) + "x" + std::to_string(h) +
                                      " (corrupt header?)");
        const Imf::ChannelList& channels = header.channels();
        int count = 0;
        if (channels.findChannel("R") && channels.findChannel("G") && channels.findChannel("B"))
            count = 3;
        else if (channels.findChannel("Y"))
            count = 1;
        if (count == 0) {
            std::string found;
            for (auto it = channels.begin(); it != channels.end(); ++it)
                found += (found.empty() ? "" : ", ") + escapedControls(it.name());
            throw fileError(path, "EXR without R, G, B or Y channels (it has: " + (found.empty() ? "none" : found) + ")");
        }
        Image image(int(w), int(h), count);
        const size_t xStride = sizeof(float) * size_t(count);
        Imf::FrameBuffer frame;
        const std::vector<const char*> names = channelNames(count);
        for (size_t c = 0; c < names.size(); ++c)
            frame.insert(names[c], Imf::Slice::Make(Imf::FLOAT, image.data.data() + c, data, xStride,
                                                    xStride * size_t(w)));
        file.setFrameBuffer(frame);
        file.readPixels(data.min.y, data.max.y);
        if (meta) {
            const int64_t dw = int64_t(display.max.x) - display.min.x + 1, dh = int64_t(display.max.y) - display.min.y + 1;
            const int64_t x0 = int64_t(data.min.x) - display.min.x, y0 = int64_t(data.min.y) - display.min.y;
            constexpr int64_t kLimit = int64_t(1) << 30;
            if (dw <= 0 || dh <= 0 || dw > kLimit || dh > kLimit || std::abs(x0) > kLimit || std::abs(y0) > kLimit)
                throw fileError(path, "implausible EXR display window " + std::to_string(dw) + "x" + std::to_string(dh) +
                                          " (corrupt header?)");
            *meta = ImageMeta{};
            meta->displayWidth = int(dw);
            meta->displayHeight = int(dh);
            meta->x0 = int(x0);
            meta->y0 = int(y0);
            for (auto it = header.begin(); it != header.end(); ++it)
                if (const auto* s = dynamic_cast<const Imf::StringAttribute*>(&it.attribute()))
                    meta->attributes[it.name()] = s->value();
        }
        return image;
    } catch (const Error&) {
        throw;
    } catch (const std::exception& e) {
        throw fileError(path, "cannot decode the EXR: " + oneLine(e.what()));
    }
}

}  // namespace vkray
