// Actions, just enough for applications that set up input: everything validates and is
// remembered, but the simulated system has no controllers, so no action is ever active.

#include <algorithm>

#include "sim_runtime.h"

namespace physhand::sim {
namespace {

// The text of a fixed-size name field; as long as the field when it is not terminated.
template <std::size_t N>
std::string_view field_text(const char (&field)[N]) {
    return {field, static_cast<std::size_t>(std::find(field, field + N, '\0') - field)};
}

// Action and action set names: non-empty, of lower-case letters, digits, '-', '_', '.'.
template <std::size_t N, std::size_t M>
XrResult check_names(const char (&name)[N], const char (&localized)[M]) {
    std::string_view text = field_text(name);
    if (text.empty() || text.size() == N) return XR_ERROR_NAME_INVALID;
    if (!std::all_of(text.begin(), text.end(), is_name_char)) return XR_ERROR_NAME_INVALID;
    std::size_t localized_size = field_text(localized).size();
    if (localized_size == 0 || localized_size == M) return XR_ERROR_LOCALIZED_NAME_INVALID;
    return XR_SUCCESS;
}

bool is_attached_to(const ActionSetData& set, XrSession session) {
    return std::find(set.attached_to.begin(), set.attached_to.end(), session) !=
           set.attached_to.end();
}

bool is_valid_action_type(XrActionType type) {
    switch (type) {
        case XR_ACTION_TYPE_BOOLEAN_INPUT:
        case XR_ACTION_TYPE_FLOAT_INPUT:
        case XR_ACTION_TYPE_VECTOR2F_INPUT:
        case XR_ACTION_TYPE_POSE_INPUT:
        case XR_ACTION_TYPE_VIBRATION_OUTPUT:
            return true;
        default:
            return false;
    }
}

// An action of a set attached to the session, of the given type (any when nullopt).
XrResult check_action(Runtime& rt, XrSession session, XrAction handle,
                      std::optional<XrActionType> type = std::nullopt) {
    const ActionData* action = rt.actions.find(handle);
    if (action == nullptr) return XR_ERROR_HANDLE_INVALID;
    if (!is_attached_to(*rt.action_sets.find(action->action_set), session)) {
        return XR_ERROR_ACTIONSET_NOT_ATTACHED;
    }
    return type && action->type != *type ? XR_ERROR_ACTION_TYPE_MISMATCH : XR_SUCCESS;
}

// The shared body of xrGetActionState*: validates, then reports an inactive action.
template <typename State>
XrResult get_action_state(XrSession session, const XrActionStateGetInfo* getInfo, State* state,
                          XrStructureType state_type, XrActionType action_type) {
    return guarded([&](Runtime& rt) {
        if (rt.sessions.find(session) == nullptr) return XR_ERROR_HANDLE_INVALID;
        if (!has_type(getInfo, XR_TYPE_ACTION_STATE_GET_INFO) || !has_type(state, state_type)) {
            return XR_ERROR_VALIDATION_FAILURE;
        }
        if (XrResult result = check_action(rt, session, getInfo->action, action_type);
            XR_FAILED(result)) {
            return result;
        }
        State inactive{};
        inactive.type = state_type;
        inactive.next = state->next;
        *state = inactive;
        return XR_SUCCESS;
    });
}

// The shared body of xrApplyHapticFeedback and xrStopHapticFeedback: with no controllers
// there is nothing to vibrate.
XrResult haptic(XrSession session, const XrHapticActionInfo* hapticActionInfo,
                const XrHapticBaseHeader* hapticFeedback, bool apply) {
    return guarded([&](Runtime& rt) {
        if (rt.sessions.find(session) == nullptr) return XR_ERROR_HANDLE_INVALID;
        if (!has_type(hapticActionInfo, XR_TYPE_HAPTIC_ACTION_INFO) ||
            (apply && !has_type(hapticFeedback, XR_TYPE_HAPTIC_VIBRATION))) {
            return XR_ERROR_VALIDATION_FAILURE;
        }
        return check_action(rt, session, hapticActionInfo->action, XR_ACTION_TYPE_VIBRATION_OUTPUT);
    });
}

}  // namespace

void destroy_action_set(Runtime& rt, XrActionSet action_set) {
    rt.actions.erase_if(
        [&](XrAction, const ActionData& action) { return action.action_set == action_set; });
    rt.action_sets.erase(action_set);
}

XrResult xrCreateActionSet(XrInstance instance, const XrActionSetCreateInfo* createInfo,
                           XrActionSet* actionSet) {
    return guarded([&](Runtime& rt) {
        if (rt.instances.find(instance) == nullptr) return XR_ERROR_HANDLE_INVALID;
        if (!has_type(createInfo, XR_TYPE_ACTION_SET_CREATE_INFO) || actionSet == nullptr) {
            return XR_ERROR_VALIDATION_FAILURE;
        }
        if (XrResult result =
                check_names(createInfo->actionSetName, createInfo->localizedActionSetName);
            XR_FAILED(result)) {
            return result;
        }
        bool duplicate = false;
        rt.action_sets.for_each([&](XrActionSet, const ActionSetData& set) {
            duplicate |= set.instance == instance && set.name == createInfo->actionSetName;
        });
        if (duplicate) return XR_ERROR_NAME_DUPLICATED;
        *actionSet = rt.action_sets.add({instance, createInfo->actionSetName, {}});
        return XR_SUCCESS;
    });
}

XrResult xrDestroyActionSet(XrActionSet actionSet) {
    return guarded([&](Runtime& rt) {
        if (rt.action_sets.find(actionSet) == nullptr) return XR_ERROR_HANDLE_INVALID;
        destroy_action_set(rt, actionSet);
        return XR_SUCCESS;
    });
}

XrResult xrCreateAction(XrActionSet actionSet, const XrActionCreateInfo* createInfo,
                        XrAction* action) {
    return guarded([&](Runtime& rt) {
        const ActionSetData* set = rt.action_sets.find(actionSet);
        if (set == nullptr) return XR_ERROR_HANDLE_INVALID;
        if (!has_type(createInfo, XR_TYPE_ACTION_CREATE_INFO) || action == nullptr ||
            !is_valid_action_type(createInfo->actionType) ||
            (createInfo->countSubactionPaths > 0 && createInfo->subactionPaths == nullptr)) {
            return XR_ERROR_VALIDATION_FAILURE;
        }
        if (XrResult result = check_names(createInfo->actionName, createInfo->localizedActionName);
            XR_FAILED(result)) {
            return result;
        }
        const InstanceData& instance = *rt.instances.find(set->instance);
        for (uint32_t i = 0; i < createInfo->countSubactionPaths; ++i) {
            if (!path_exists(instance, createInfo->subactionPaths[i])) return XR_ERROR_PATH_INVALID;
        }
        if (!set->attached_to.empty()) return XR_ERROR_ACTIONSETS_ALREADY_ATTACHED;
        bool duplicate = false;
        rt.actions.for_each([&](XrAction, const ActionData& existing) {
            duplicate |=
                existing.action_set == actionSet && existing.name == createInfo->actionName;
        });
        if (duplicate) return XR_ERROR_NAME_DUPLICATED;
        *action = rt.actions.add({actionSet, createInfo->actionName, createInfo->actionType});
        return XR_SUCCESS;
    });
}

XrResult xrDestroyAction(XrAction action) {
    return guarded([&](Runtime& rt) {
        if (rt.actions.find(action) == nullptr) return XR_ERROR_HANDLE_INVALID;
        rt.actions.erase(action);
        return XR_SUCCESS;
    });
}

XrResult xrSuggestInteractionProfileBindings(
    XrInstance instance, const XrInteractionProfileSuggestedBinding* suggestedBindings) {
    return guarded([&](Runtime& rt) {
        const InstanceData* data = rt.instances.find(instance);
        if (data == nullptr) return XR_ERROR_HANDLE_INVALID;
        if (!has_type(suggestedBindings, XR_TYPE_INTERACTION_PROFILE_SUGGESTED_BINDING) ||
            suggestedBindings->countSuggestedBindings == 0 ||
            suggestedBindings->suggestedBindings == nullptr) {
            return XR_ERROR_VALIDATION_FAILURE;
        }
        if (!path_exists(*data, suggestedBindings->interactionProfile)) {
            return XR_ERROR_PATH_INVALID;
        }
        // Any profile is accepted: with no controllers, no binding is ever used.
        for (uint32_t i = 0; i < suggestedBindings->countSuggestedBindings; ++i) {
            const XrActionSuggestedBinding& binding = suggestedBindings->suggestedBindings[i];
            const ActionData* action = rt.actions.find(binding.action);
            if (action == nullptr) return XR_ERROR_HANDLE_INVALID;
            if (!path_exists(*data, binding.binding)) return XR_ERROR_PATH_INVALID;
            if (!rt.action_sets.find(action->action_set)->attached_to.empty()) {
                return XR_ERROR_ACTIONSETS_ALREADY_ATTACHED;
            }
        }
        return XR_SUCCESS;
    });
}

XrResult xrAttachSessionActionSets(XrSession session,
                                   const XrSessionActionSetsAttachInfo* attachInfo) {
    return guarded([&](Runtime& rt) {
        SessionData* data = rt.sessions.find(session);
        if (data == nullptr) return XR_ERROR_HANDLE_INVALID;
        if (!has_type(attachInfo, XR_TYPE_SESSION_ACTION_SETS_ATTACH_INFO) ||
            attachInfo->countActionSets == 0 || attachInfo->actionSets == nullptr) {
            return XR_ERROR_VALIDATION_FAILURE;
        }
        if (data->actions_attached) return XR_ERROR_ACTIONSETS_ALREADY_ATTACHED;
        for (uint32_t i = 0; i < attachInfo->countActionSets; ++i) {
            if (rt.action_sets.find(attachInfo->actionSets[i]) == nullptr) {
                return XR_ERROR_HANDLE_INVALID;
            }
        }
        for (uint32_t i = 0; i < attachInfo->countActionSets; ++i) {
            rt.action_sets.find(attachInfo->actionSets[i])->attached_to.push_back(session);
        }
        data->actions_attached = true;
        return XR_SUCCESS;
    });
}

XrResult xrSyncActions(XrSession session, const XrActionsSyncInfo* syncInfo) {
    return guarded([&](Runtime& rt) {
        const SessionData* data = rt.sessions.find(session);
        if (data == nullptr) return XR_ERROR_HANDLE_INVALID;
        if (!has_type(syncInfo, XR_TYPE_ACTIONS_SYNC_INFO) ||
            (syncInfo->countActiveActionSets > 0 && syncInfo->activeActionSets == nullptr)) {
            return XR_ERROR_VALIDATION_FAILURE;
        }
        for (uint32_t i = 0; i < syncInfo->countActiveActionSets; ++i) {
            const ActionSetData* set = rt.action_sets.find(syncInfo->activeActionSets[i].actionSet);
            if (set == nullptr) return XR_ERROR_HANDLE_INVALID;
            if (!is_attached_to(*set, session)) return XR_ERROR_ACTIONSET_NOT_ATTACHED;
        }
        return data->state == XR_SESSION_STATE_FOCUSED ? XR_SUCCESS : XR_SESSION_NOT_FOCUSED;
    });
}

XrResult xrGetActionStateBoolean(XrSession session, const XrActionStateGetInfo* getInfo,
                                 XrActionStateBoolean* state) {
    return get_action_state(session, getInfo, state, XR_TYPE_ACTION_STATE_BOOLEAN,
                            XR_ACTION_TYPE_BOOLEAN_INPUT);
}

XrResult xrGetActionStateFloat(XrSession session, const XrActionStateGetInfo* getInfo,
                               XrActionStateFloat* state) {
    return get_action_state(session, getInfo, state, XR_TYPE_ACTION_STATE_FLOAT,
                            XR_ACTION_TYPE_FLOAT_INPUT);
}

XrResult xrGetActionStateVector2f(XrSession session, const XrActionStateGetInfo* getInfo,
                                  XrActionStateVector2f* state) {
    return get_action_state(session, getInfo, state, XR_TYPE_ACTION_STATE_VECTOR2F,
                            XR_ACTION_TYPE_VECTOR2F_INPUT);
}

XrResult xrGetActionStatePose(XrSession session, const XrActionStateGetInfo* getInfo,
                              XrActionStatePose* state) {
    return get_action_state(session, getInfo, state, XR_TYPE_ACTION_STATE_POSE,
                            XR_ACTION_TYPE_POSE_INPUT);
}

XrResult xrCreateActionSpace(XrSession session, const XrActionSpaceCreateInfo* createInfo,
                             XrSpace* space) {
    return guarded([&](Runtime& rt) {
        if (rt.sessions.find(session) == nullptr) return XR_ERROR_HANDLE_INVALID;
        if (!has_type(createInfo, XR_TYPE_ACTION_SPACE_CREATE_INFO) || space == nullptr) {
            return XR_ERROR_VALIDATION_FAILURE;
        }
        const ActionData* action = rt.actions.find(createInfo->action);
        if (action == nullptr) return XR_ERROR_HANDLE_INVALID;
        if (action->type != XR_ACTION_TYPE_POSE_INPUT) return XR_ERROR_ACTION_TYPE_MISMATCH;
        if (!is_valid_pose(createInfo->poseInActionSpace)) return XR_ERROR_POSE_INVALID;
        *space = rt.spaces.add({session, std::nullopt, from_xr(createInfo->poseInActionSpace)});
        return XR_SUCCESS;
    });
}

XrResult xrGetCurrentInteractionProfile(XrSession session, XrPath topLevelUserPath,
                                        XrInteractionProfileState* interactionProfile) {
    return guarded([&](Runtime& rt) {
        const SessionData* data = rt.sessions.find(session);
        if (data == nullptr) return XR_ERROR_HANDLE_INVALID;
        if (!has_type(interactionProfile, XR_TYPE_INTERACTION_PROFILE_STATE)) {
            return XR_ERROR_VALIDATION_FAILURE;
        }
        if (!path_exists(*rt.instances.find(data->instance), topLevelUserPath)) {
            return XR_ERROR_PATH_INVALID;
        }
        if (!data->actions_attached) return XR_ERROR_ACTIONSET_NOT_ATTACHED;
        interactionProfile->interactionProfile = XR_NULL_PATH;  // no controller, no profile
        return XR_SUCCESS;
    });
}

XrResult xrEnumerateBoundSourcesForAction(XrSession session,
                                          const XrBoundSourcesForActionEnumerateInfo* enumerateInfo,
                                          uint32_t sourceCapacityInput, uint32_t* sourceCountOutput,
                                          XrPath* sources) {
    return guarded([&](Runtime& rt) {
        if (rt.sessions.find(session) == nullptr) return XR_ERROR_HANDLE_INVALID;
        if (!has_type(enumerateInfo, XR_TYPE_BOUND_SOURCES_FOR_ACTION_ENUMERATE_INFO)) {
            return XR_ERROR_VALIDATION_FAILURE;
        }
        if (XrResult result = check_action(rt, session, enumerateInfo->action); XR_FAILED(result)) {
            return result;
        }
        return fill_array(sourceCapacityInput, sourceCountOutput, sources, 0,
                          [](XrPath&, uint32_t) { return XR_SUCCESS; });
    });
}

// No source is ever bound, so no application has a source path to ask about; any path
// is named by its own string.
XrResult xrGetInputSourceLocalizedName(XrSession session,
                                       const XrInputSourceLocalizedNameGetInfo* getInfo,
                                       uint32_t bufferCapacityInput, uint32_t* bufferCountOutput,
                                       char* buffer) {
    XrInstance instance = XR_NULL_HANDLE;
    XrResult result = guarded([&](Runtime& rt) {
        const SessionData* data = rt.sessions.find(session);
        if (data == nullptr) return XR_ERROR_HANDLE_INVALID;
        if (!has_type(getInfo, XR_TYPE_INPUT_SOURCE_LOCALIZED_NAME_GET_INFO) ||
            getInfo->whichComponents == 0) {
            return XR_ERROR_VALIDATION_FAILURE;
        }
        instance = data->instance;
        return XR_SUCCESS;
    });
    if (XR_FAILED(result)) return result;
    return xrPathToString(instance, getInfo->sourcePath, bufferCapacityInput, bufferCountOutput,
                          buffer);
}

XrResult xrApplyHapticFeedback(XrSession session, const XrHapticActionInfo* hapticActionInfo,
                               const XrHapticBaseHeader* hapticFeedback) {
    return haptic(session, hapticActionInfo, hapticFeedback, true);
}

XrResult xrStopHapticFeedback(XrSession session, const XrHapticActionInfo* hapticActionInfo) {
    return haptic(session, hapticActionInfo, nullptr, false);
}

}  // namespace physhand::sim
