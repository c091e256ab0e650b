#include "two_dm_writer.hpp"

namespace terratin::io::detail {

namespace {

class TwoDmFormat : public MeshFormatBase {
public:
    static constexpr std::string_view kVertexMessage = "Writing nodes";
    static constexpr std::string_view kFaceMessage = "Writing elements";

    void head(BufferedFile& file, const MeshFileInfo& info, std::uint64_t, std::uint64_t) {
        file.text("MESH2D\nMESHNAME \"");
        file.text(info.name);
        file.text("\"\n");
    }

    /// Node ids count from 1.
    void vertex(BufferedFile& file, std::uint64_t number, const Point3& p) {
        file.text("ND ");
        file.number(number + 1);
        file.put(' ');
        file.number(p.x);
        file.put(' ');
        file.number(p.y);
        file.put(' ');
        file.number(p.z);
        file.put('\n');
    }

    /// Element ids and node ids count from 1.
    void face(BufferedFile& file, std::uint64_t number, std::uint32_t a, std::uint32_t b,
              std::uint32_t c) {
        file.text("E3T ");
        file.number(number + 1);
        for (const std::uint32_t corner : {a, b, c}) {
            file.put(' ');
            file.number(std::uint64_t{corner} + 1);
        }
        file.text(" 1\n");
    }
};

} // namespace

constinit const MeshWriter kTwoDmWriter = meshWriterFor<TwoDmFormat>();

} // namespace terratin::io::detail
