#pragma once
// A fresh directory per test, removed afterwards, and a listing helper.

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <set>
#include <string>

namespace terratin::test {

class TemporaryDirectory {
public:
    TemporaryDirectory() {
        std::random_device device;
        m_path = std::filesystem::temp_directory_path() /
                 ("terratin-test-" + std::to_string(::getpid()) + "-" + std::to_string(device()));
        std::filesystem::create_directories(m_path);
    }
    ~TemporaryDirectory() {
        std::error_code ignored;
        std::filesystem::remove_all(m_path, ignored);
    }
    TemporaryDirectory(const TemporaryDirectory&) = delete;
    TemporaryDirectory& operator=(const TemporaryDirectory&) = delete;

    [[nodiscard]] const std::filesystem::path& path() const { return m_path; }
    [[nodiscard]] std::filesystem::path operator/(const std::string& name) const {
        return m_path / name;
    }
    /// The path of `name` in the directory, as text (for APIs that take strings).
    [[nodiscard]] std::string file(const std::string& name) const {
        return (m_path / name).string();
    }
    /// Names of the entries in the directory.
    [[nodiscard]] std::set<std::string> entries() const { return entriesOf(m_path); }
    /// Names of the entries in `directory`.
    [[nodiscard]] static std::set<std::string> entriesOf(const std::filesystem::path& directory) {
        std::set<std::string> names;
        for (const auto& entry : std::filesystem::directory_iterator(directory))
            names.insert(entry.path().filename().string());
        return names;
    }

private:
    std::filesystem::path m_path;
};

inline std::string fileBytes(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

} // namespace terratin::test
