// Typed attributes of a mesh's vertices or tets: named columns, one value
// per entity id, that grow with the entities, take their initial value
// when an entity is made (or its id reused), and follow every
// renumbering (Mesh::compact). The layers above the topology keep their
// per-entity state here rather than in the Mesh: the metric and its
// logarithm, the CAD parameters, a background's tets, the quality cache,
// and a distributed part's global ids; a user may add columns of their own
// (Omega_h's tags, pmp's properties).
//
// A column's values are read and written directly by id (operator[]), so
// a pass holding an entity's vertices may write its value on any thread;
// adding or removing a column is done outside parallel passes.
#pragma once

#include <metrica/mesh_array.hpp>
#include <metrica/part_runner.hpp>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <typeinfo>
#include <utility>
#include <vector>

namespace metrica {

// What the ids past the end hold when room is added for a parallel pass
// (Mesh::add_dead_room): left unwritten (the entity's making writes its
// value: cheap for room no one takes), or the initial value (read for
// dead entities too).
enum class DeadRoomFill : std::uint8_t { unwritten, initial };

class AttributeColumn {
 public:
  explicit AttributeColumn(std::string name) : name_(std::move(name)) {}
  virtual ~AttributeColumn() = default;
  AttributeColumn(const AttributeColumn&) = default;
  AttributeColumn& operator=(const AttributeColumn&) = delete;

  const std::string& name() const { return name_; }
  virtual const std::type_info& value_type() const = 0;
  virtual std::size_t size() const = 0;
  virtual std::size_t bytes() const = 0;
  virtual std::unique_ptr<AttributeColumn> clone() const = 0;

  // The mesh's operations on every column (mesh.cpp, compact.cpp).
  virtual void reserve(std::size_t n) = 0;
  virtual void append_initial() = 0;
  virtual void set_initial(std::size_t id) = 0;
  virtual void add_room(std::size_t size, std::size_t capacity, const PartRunner& run) = 0;
  // Value i moves to new_of_old[i] (kNoId: dropped) in a column of `size`.
  virtual void renumber(std::span<const std::uint32_t> new_of_old, std::size_t size, const PartRunner& run) = 0;

 private:
  std::string name_;
};

template <class T>
class Attribute final : public AttributeColumn {
 public:
  Attribute(std::string name, std::size_t size, const T& initial, DeadRoomFill fill)
      : AttributeColumn(std::move(name)), initial_(initial), fill_(fill) {
    values_.assign(size, initial);
  }

  T& operator[](std::size_t id) { return values_[id]; }
  const T& operator[](std::size_t id) const { return values_[id]; }
  T* data() { return values_.data(); }
  const T* data() const { return values_.data(); }
  std::span<T> values() { return values_; }
  std::span<const T> values() const { return values_; }
  const T& initial() const { return initial_; }
  // Every value set to v (outside parallel passes).
  void fill(const T& v) { std::fill(values_.begin(), values_.end(), v); }

  const std::type_info& value_type() const override { return typeid(T); }
  std::size_t size() const override { return values_.size(); }
  std::size_t bytes() const override { return values_.capacity() * sizeof(T); }
  std::unique_ptr<AttributeColumn> clone() const override { return std::make_unique<Attribute>(*this); }
  void reserve(std::size_t n) override { values_.reserve(n); }
  void append_initial() override { values_.push_back(initial_); }
  void set_initial(std::size_t id) override { values_[id] = initial_; }
  void add_room(std::size_t size, std::size_t capacity, const PartRunner& run) override {
    if (fill_ == DeadRoomFill::initial)
      grow_array(values_, size, initial_, capacity, run);
    else
      extend_array(values_, size, capacity, run);
  }
  void renumber(std::span<const std::uint32_t> new_of_old, std::size_t size, const PartRunner& run) override {
    permute_to(values_, new_of_old, size, run);
  }

 private:
  MeshArray<T> values_;
  T initial_;
  DeadRoomFill fill_;
};

// The columns of one kind of entity (vertices or tets) of a mesh, by name.
// Copying a table copies its columns; the columns themselves stay where
// they are while the table exists (a reference to one stays good until
// it is removed), so a mesh may keep pointers to its own.
class AttributeTable {
 public:
  AttributeTable() = default;
  AttributeTable(const AttributeTable& o) {
    columns_.reserve(o.columns_.size());
    for (const auto& c : o.columns_) columns_.push_back(c->clone());
  }
  AttributeTable& operator=(const AttributeTable& o) {
    if (this != &o) *this = AttributeTable(o);
    return *this;
  }
  AttributeTable(AttributeTable&&) noexcept = default;
  AttributeTable& operator=(AttributeTable&&) noexcept = default;

  // A new column of `size` values (the entities' capacity), each `initial`.
  // Throws when the name is taken.
  template <class T>
  Attribute<T>& add(std::string name, std::size_t size, const T& initial, DeadRoomFill fill = DeadRoomFill::unwritten) {
    if (find_column(name)) throw std::invalid_argument("an attribute named '" + name + "' exists already");
    auto column = std::make_unique<Attribute<T>>(std::move(name), size, initial, fill);
    Attribute<T>& a = *column;
    columns_.push_back(std::move(column));
    return a;
  }
  // The column of that name and type; null when there is none. Throws
  // when a column of that name holds another type.
  template <class T>
  Attribute<T>* find(std::string_view name) {
    AttributeColumn* c = find_column(name);
    if (!c) return nullptr;
    if (c->value_type() != typeid(T))
      throw std::invalid_argument("the attribute '" + std::string(name) + "' holds another type");
    return static_cast<Attribute<T>*>(c);
  }
  template <class T>
  const Attribute<T>* find(std::string_view name) const {
    return const_cast<AttributeTable*>(this)->find<T>(name);
  }
  // Removes the column (references to it become invalid); false when
  // there is none.
  bool remove(std::string_view name) {
    for (auto it = columns_.begin(); it != columns_.end(); ++it)
      if ((*it)->name() == name) {
        columns_.erase(it);
        return true;
      }
    return false;
  }
  std::size_t size() const { return columns_.size(); }
  template <class F>
  void for_each(F&& f) {
    for (auto& c : columns_) f(*c);
  }
  std::vector<std::string> names() const {
    std::vector<std::string> n;
    for (const auto& c : columns_) n.push_back(c->name());
    return n;
  }

  // The mesh's operations, applied to every column.
  void reserve(std::size_t n) {
    for (auto& c : columns_) c->reserve(n);
  }
  void append_initial() {
    for (auto& c : columns_) c->append_initial();
  }
  void add_room(std::size_t size, std::size_t capacity, const PartRunner& run) {
    for (auto& c : columns_) c->add_room(size, capacity, run);
  }
  void renumber(std::span<const std::uint32_t> new_of_old, std::size_t size, const PartRunner& run) {
    for (auto& c : columns_) c->renumber(new_of_old, size, run);
  }

 private:
  AttributeColumn* find_column(std::string_view name) const {
    for (const auto& c : columns_)
      if (c->name() == name) return c.get();
    return nullptr;
  }
  std::vector<std::unique_ptr<AttributeColumn>> columns_;
};

}  // namespace metrica
